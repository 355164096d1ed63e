#!/usr/bin/python3
"""Microgrid demosaic + Stokes speed: tirpol's Python binding against an OpenCV + numpy equivalent of
polanalyser's method, on the same seeded 640x512 16-bit Sony-layout frames, in one run.

Usage (from the repository root, with the Python module built):

    PYTHONPATH=build/python /usr/bin/python3 bench/microgrid_vs_opencv.py [--repeats N] [--frames N]

Both sides run on one core: tirpol's demosaic_microgrid / reduce_stokes have no threads option and run
single-threaded; OpenCV is set to one thread (cv2.setNumThreads(1)) and BLAS to one thread
(OPENBLAS_NUM_THREADS etc. set before numpy is imported, unless already set).

The reference is NOT polanalyser (a PyPI package, not reachable here): it is written for this benchmark
from polanalyser's documentation of its method, no code copied: demosaicing as polanalyser's
demosaicing(..., COLOR_PolarMono) describes it (OpenCV's bilinear Bayer conversion run twice on the
16-bit mosaic, once with the 0/90 deg pixels in the red/blue places and once with the 45/135 deg ones,
keeping red and blue), then calcStokes (S = pinv(A) I with ideal analyzer rows 1/2 (1, cos 2t, sin 2t))
and cvtStokesToDoLP (sqrt(S1^2 + S2^2) / S0) in numpy. Exits 0 with "skipped: ..." when cv2 is missing.
"""
import argparse
import os
import subprocess
import sys
import time

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import numpy as np  # noqa: E402

try:
    import cv2  # noqa: E402
except ImportError as error:
    print(f"skipped: cv2 not importable ({error}); install python3-opencv to run this benchmark")
    sys.exit(0)

try:
    import tirpol.calibration  # noqa: E402
except ImportError as error:
    sys.exit(f"error: tirpol not importable ({error}); build the Python module and set "
             "PYTHONPATH=build/python")

WIDTH, HEIGHT = 640, 512
# Sony IMX250MZR layout: analyzer angle at cell positions (0,0), (0,1), (1,0), (1,1).
SONY_PATTERN_DEG = {(0, 0): 90.0, (0, 1): 45.0, (1, 0): 135.0, (1, 1): 0.0}
ANGLES_DEG = (0.0, 45.0, 90.0, 135.0)
# The same-method agreement tolerance, counts. OpenCV's 16-bit bilinear Bayer conversion rounds each
# interpolated value to an integer (error <= 0.5 per plane); with ideal 0/45/90/135 analyzers
# S0 = (I0 + I45 + I90 + I135) / 2, S1 = I0 - I90, S2 = I45 - I135, so each Stokes value can differ by
# at most 1 count from tirpol's float demosaic, plus float32 rounding of tirpol's values (~0.004 at
# 40000 counts).
AGREEMENT_TOLERANCE_COUNTS = 1.01
BORDER_PX = 2  # OpenCV and tirpol treat the outer pixels differently (replicate vs mirror)


def seeded_frames(count, seed):
    """Sony-layout mosaics of a smooth polarized scene (S0 18000-30000 counts, DoLP 0.05-0.35, AoP
    swinging over the frame) with Gaussian noise sigma = 30 counts, as uint16."""
    rng = np.random.default_rng(seed)
    y, x = np.mgrid[0:HEIGHT, 0:WIDTH].astype(np.float64)
    frames = []
    for _ in range(count):
        phase = rng.uniform(0, 2 * np.pi, size=3)
        s0 = 24000 + 6000 * np.sin(x / 57 + phase[0]) * np.cos(y / 43 + phase[1])
        dolp = 0.2 + 0.15 * np.sin((x + y) / 90 + phase[2])
        aop = np.deg2rad(30 + 60 * np.sin(x / 150) * np.cos(y / 110))
        s1, s2 = s0 * dolp * np.cos(2 * aop), s0 * dolp * np.sin(2 * aop)
        mosaic = np.empty((HEIGHT, WIDTH))
        for (row, col), angle_deg in SONY_PATTERN_DEG.items():
            t = np.deg2rad(2 * angle_deg)
            cell = (slice(row, None, 2), slice(col, None, 2))
            mosaic[cell] = 0.5 * (s0[cell] + s1[cell] * np.cos(t) + s2[cell] * np.sin(t))
        mosaic += rng.normal(0, 30, size=mosaic.shape)
        frames.append(np.clip(np.rint(mosaic), 0, 65535).astype(np.uint16))
    return frames


def check_bayer_codes():
    """Which OpenCV Bayer code puts which analyzer phase in the blue and red channels, checked on a
    mosaic whose four phases are constants, so that a wrong code fails loudly rather than silently
    swapping angles."""
    mosaic = np.zeros((8, 8), np.uint16)
    for (row, col), angle_deg in SONY_PATTERN_DEG.items():
        mosaic[row::2, col::2] = 1000 + 10 * int(angle_deg)
    expected = {}
    for code_name, blue_deg, red_deg in (("COLOR_BayerBG2BGR", 0, 90), ("COLOR_BayerGR2BGR", 45, 135)):
        bgr = cv2.cvtColor(mosaic, getattr(cv2, code_name))
        inner = bgr[2:-2, 2:-2]
        for channel, angle_deg in ((0, blue_deg), (2, red_deg)):
            if not np.all(inner[..., channel] == 1000 + 10 * angle_deg):
                sys.exit(f"error: {code_name} channel {channel} is not the {angle_deg} deg phase")
        expected[code_name] = (blue_deg, red_deg)
    return expected


# Ideal analyzer matrix, rows 1/2 (1, cos 2t, sin 2t) for the planes in ANGLES_DEG order.
_t = np.deg2rad(2 * np.array(ANGLES_DEG))
ANALYZER_PINV = np.linalg.pinv(0.5 * np.stack([np.ones_like(_t), np.cos(_t), np.sin(_t)], axis=1))


def opencv_numpy_stokes(mosaic):
    """The polanalyser-equivalent path: two Bayer conversions, then S = pinv(A) I and DoLP."""
    bgr_0_90 = cv2.cvtColor(mosaic, cv2.COLOR_BayerBG2BGR)  # blue = 0 deg, red = 90 deg
    bgr_45_135 = cv2.cvtColor(mosaic, cv2.COLOR_BayerGR2BGR)  # blue = 45 deg, red = 135 deg
    intensities = np.stack(
        [bgr_0_90[..., 0], bgr_45_135[..., 0], bgr_0_90[..., 2], bgr_45_135[..., 2]], axis=-1)
    stokes = np.tensordot(intensities.astype(np.float64), ANALYZER_PINV, axes=(-1, 1))
    s0, s1, s2 = stokes[..., 0], stokes[..., 1], stokes[..., 2]
    dolp = np.sqrt(s1**2 + s2**2) / s0
    return s0, s1, s2, dolp


def opencv_demosaic_only(mosaic):
    return (cv2.cvtColor(mosaic, cv2.COLOR_BayerBG2BGR), cv2.cvtColor(mosaic, cv2.COLOR_BayerGR2BGR))


def tirpol_stokes(mosaic, method):
    image = tirpol.calibration.reduce_microgrid(mosaic, pattern="sony", method=method)
    return image["S0"], image["S1"], image["S2"], image["DoLP"]


def ms_per_frame(functions, frames, repeats):
    """Best time per frame of each function; the passes are interleaved (each pass runs every
    function over all frames in turn) so that a change of machine load hits all of them alike."""
    for function in functions:  # warm-up: first calls, caches, allocator
        for frame in frames[:2]:
            function(frame)
    best = [float("inf")] * len(functions)
    for _ in range(repeats):
        for k, function in enumerate(functions):
            start = time.perf_counter()
            for frame in frames:
                function(frame)
            best[k] = min(best[k], (time.perf_counter() - start) / len(frames))
    return [seconds * 1e3 for seconds in best]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=8, help="distinct seeded frames per pass")
    parser.add_argument("--repeats", type=int, default=5, help="timed passes; the fastest is kept")
    parser.add_argument("--seed", type=int, default=28)
    args = parser.parse_args()
    if args.frames < 1 or args.repeats < 1:
        sys.exit("error: --frames and --repeats must be >= 1")

    cv2.setNumThreads(1)
    check_bayer_codes()
    frames = seeded_frames(args.frames, args.seed)

    interior = (slice(BORDER_PX, -BORDER_PX), slice(BORDER_PX, -BORDER_PX))
    reference = opencv_numpy_stokes(frames[0])
    ours = tirpol_stokes(frames[0], "bilinear")
    worst = 0.0
    print(f"agreement, tirpol bilinear vs OpenCV+numpy, frame 0, pixels >= {BORDER_PX} px from the "
          f"border (tolerance {AGREEMENT_TOLERANCE_COUNTS} counts):")
    for name, a, b in zip(("S0", "S1", "S2"), ours, reference):
        diff = np.abs(a[interior].astype(np.float64) - b[interior])
        worst = max(worst, diff.max())
        print(f"  {name}: max |diff| {diff.max():.4f} counts, RMS {np.sqrt(np.mean(diff**2)):.4f}")
    dolp_diff = np.abs(ours[3][interior] - reference[3][interior]).max()
    print(f"  DoLP: max |diff| {dolp_diff:.2e}")
    newton = tirpol_stokes(frames[0], "newton")
    for name, a, b in zip(("S0", "S1", "S2"), newton, reference):
        rms = np.sqrt(np.mean((a[interior].astype(np.float64) - b[interior]) ** 2))
        print(f"  (different method) tirpol newton vs OpenCV bilinear {name}: RMS {rms:.3f} counts")

    rows = [
        ("OpenCV+numpy (polanalyser-equivalent, bilinear)", opencv_numpy_stokes),
        ("tirpol reduce_microgrid, bilinear", lambda f: tirpol_stokes(f, "bilinear")),
        ("tirpol reduce_microgrid, newton", lambda f: tirpol_stokes(f, "newton")),
        ("tirpol reduce_microgrid, super-pixel", lambda f: tirpol_stokes(f, "super-pixel")),
        # Where the time goes: the demosaicing alone on each side.
        ("demosaic only: OpenCV, two Bayer conversions", opencv_demosaic_only),
        ("demosaic only: tirpol.calibration.demosaic, bilinear",
         lambda f: tirpol.calibration.demosaic(f, pattern="sony", method="bilinear")),
    ]
    times = list(zip([name for name, _ in rows],
                     ms_per_frame([function for _, function in rows], frames, args.repeats)))
    reference_ms = times[0][1]
    print(f"\n{WIDTH}x{HEIGHT} uint16 -> S0 S1 S2 DoLP, one thread, best of {args.repeats} interleaved "
          f"passes over {args.frames} frames, load average {os.getloadavg()[0]:.1f} "
          f"({os.cpu_count()} CPUs), OpenCV {cv2.__version__}, numpy {np.__version__}")
    print("| path | ms per frame | frames/s | speed vs OpenCV+numpy |")
    print("|---|---|---|---|")
    for name, ms in times:
        if name.startswith("demosaic only"):
            print(f"| {name} | {ms:.2f} | {1e3 / ms:.0f} | |")
            continue
        print(f"| {name} | {ms:.2f} | {1e3 / ms:.0f} | {reference_ms / ms:.2f}x |")

    if worst > AGREEMENT_TOLERANCE_COUNTS:
        print(f"FAILED: tirpol bilinear and OpenCV+numpy differ by {worst:.3f} counts "
              f"> {AGREEMENT_TOLERANCE_COUNTS}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
