"""Run by check_clean_debian.sh inside the clean Debian 12 root, as an ordinary user, with Debian's
python3 and no PYTHONPATH: the installed tirpol package reduces a synthetic analyzer frame set.

Four ideal-polarizer images (Malus's law, core.linear_polarizer) of a field whose right half is
partially polarized (DoLP 0.3, AoP 20°) and whose left half is unpolarized, with Gaussian noise of
known σ; calibration.reduce must give back DoLP and AoP within a few standard errors of the means,
propagate σ, and the Stokes image must survive an EXR round trip. Exit status 0 when all hold.
"""

import math
import os
import sys
import tempfile

import numpy as np

import tirpol
from tirpol import calibration, core

where = os.path.realpath(tirpol.__file__)
print(f"tirpol imported from {where}")
assert where.startswith("/usr/lib/python3"), f"tirpol imported from {where}, not Debian's dist-packages"

height, width = 48, 64
s0, dolp_true, aop_true_deg, noise = 1000.0, 0.3, 20.0, 2.0
truth = np.zeros((height, width, 4))
truth[..., 0] = s0
right = np.s_[:, width // 2 :]
left = np.s_[:, : width // 2]
truth[right] = core.linearly_polarized(s0, dolp_true, aop_true_deg)

rng = np.random.default_rng(7)
angles = (0.0, 45.0, 90.0, 135.0)
images = {
    a: (truth @ core.linear_polarizer(a)[0] + rng.normal(0.0, noise, (height, width))).astype(np.float32)
    for a in angles
}
stds = {a: np.full((height, width), noise, np.float32) for a in angles}
stokes = calibration.reduce(images, stds)

dolp = np.asarray(stokes["DoLP"], dtype=float)
aop = np.asarray(stokes["AoP"], dtype=float)
s1 = np.asarray(stokes["S1"], dtype=float)
s2 = np.asarray(stokes["S2"], dtype=float)
# DoLP of the right half's mean Stokes vector: its standard error is σ_S1 / S0 per pixel over √n.
n = dolp[right].size
dolp_of_mean = math.hypot(s1[right].mean(), s2[right].mean()) / np.asarray(stokes["S0"])[right].mean()
sigma_s1 = float(np.asarray(stokes["S1_std"])[right].mean())
standard_error = sigma_s1 / s0 / math.sqrt(n)
print(f"DoLP of the polarized half {dolp_of_mean:.5f} (true {dolp_true}, standard error {standard_error:.2e}), "
      f"unpolarized half mean DoLP {dolp[left].mean():.5f}")
assert abs(dolp_of_mean - dolp_true) < 5 * standard_error, dolp_of_mean
# σ of S1 for an ideal 4-angle reduction with σ per image: S1 = I0 − I90, so √2·σ.
assert abs(sigma_s1 - math.sqrt(2) * noise) < 1e-3 * noise, sigma_s1
# AoP is in degrees in [0, 180) (docs/conventions.md) and axial: the circular mean of 2·AoP.
aop_rad = np.deg2rad(aop[right])
aop_mean_deg = math.degrees(0.5 * math.atan2(np.sin(2 * aop_rad).mean(), np.cos(2 * aop_rad).mean()))
print(f"AoP of the polarized half {aop_mean_deg:.3f} deg (true {aop_true_deg})")
assert abs(aop_mean_deg - aop_true_deg) < 0.1, aop_mean_deg
# The unpolarized half: DoLP there is noise only (σ_S1/S0 ≈ 0.003 per pixel), far below 0.3.
assert dolp[left].mean() < 0.02, dolp[left].mean()

with tempfile.TemporaryDirectory() as folder:
    path = os.path.join(folder, "reduced.exr")
    core.write_exr(path, stokes)
    back = core.read_exr(path)
    assert np.allclose(np.asarray(back["S1"]), s1, rtol=1e-6, atol=1e-3), "EXR round trip changed S1"
print("python check passed")
sys.exit(0)
