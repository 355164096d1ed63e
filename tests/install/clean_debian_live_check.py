"""Run by check_clean_debian.sh inside the clean Debian 12 root against the installed `tirpol live`
serving the simulated rig (the digital twin's scene camera behind the in-process simulated stage) on
loopback: the page and its assets are served, the camera renders frames that follow the stage's
angle, and the Stokes images of a complete polarizer cycle show polarization.

clean_debian_live_check.py PORT WIDTH HEIGHT [TIMEOUT_S]

Polarization criterion (the one of the live end-to-end test
LiveEndToEnd.TheSceneCameraBehindASimulatedStageShowsPolarization): over the middle quarter of the
image, the degree of linear polarization of the mean Stokes vector, hypot(mean S1, mean S2) / mean S0,
exceeds 5 standard errors of that numerator and 1e-3. The mean of per-pixel DoLP is no evidence (noise
alone makes it positive). Exit status 0 when everything holds; each failure is printed.
"""

import json
import math
import sys
import time
import urllib.request

port, width, height = int(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3])
timeout_s = float(sys.argv[4]) if len(sys.argv) > 4 else 300.0
base = f"http://127.0.0.1:{port}"


def get(path):
    with urllib.request.urlopen(base + path, timeout=30) as response:
        return response.status, response.headers, response.read()


def get_json(path):
    status, _, body = get(path)
    if status != 200:
        sys.exit(f"GET {path}: HTTP {status}")
    return json.loads(body)


for asset, marker in (("/", b"<html"), ("/live.js", b"function"), ("/live.css", b"{")):
    status, headers, body = get(asset)
    if status != 200 or marker not in body.lower():
        sys.exit(f"GET {asset}: HTTP {status}, {len(body)} bytes without {marker!r}: page asset missing")
    print(f"ok   GET {asset}: {len(body)} bytes ({headers.get('Content-Type')})")

describe = get_json("/api/describe")
camera = describe["camera"]
print(f"ok   camera {camera['uri']} {camera['width']}x{camera['height']}, stage {describe['stage']}, "
      f"angles {describe['angles_deg']}")
if (camera["width"], camera["height"]) != (width, height) or not describe["stage"]:
    sys.exit(f"/api/describe: expected a {width}x{height} camera behind a stage, got {json.dumps(describe)}")

# Two complete cycles: the first may have begun while the stage was still reaching 0°.
deadline = time.monotonic() + timeout_s
angles_seen = set()
while True:
    status = get_json("/api/status")
    stage = status.get("stage") or {}
    if stage.get("error") or status["camera"].get("error"):
        sys.exit(f"/api/status reports an error: {json.dumps(status)}")
    if stage.get("angle_deg") is not None:
        angles_seen.add(round(stage["angle_deg"]))
    if stage.get("cycles", 0) >= 2:
        break
    if time.monotonic() > deadline:
        sys.exit(f"no 2 complete polarizer cycles within {timeout_s:.0f} s: {json.dumps(status)}")
    time.sleep(0.5)
print(f"ok   {stage['cycles']} polarizer cycles, {status['camera']['delivered']} frames delivered, "
      f"stage read back at {sorted(angles_seen)} deg")

status_code, headers, body = get("/api/stokes?after=0")
if status_code != 200 or not body:
    sys.exit(f"GET /api/stokes?after=0: HTTP {status_code}, {len(body)} bytes")
print(f"ok   GET /api/stokes: {len(body)} bytes (sequence {headers.get('X-Sequence')})")

x0, y0, x1, y1 = width // 4, height // 4, 3 * width // 4 - 1, 3 * height // 4 - 1
readout = get_json(f"/api/region?x0={x0}&y0={y0}&x1={x1}&y1={y1}&dolp_min=0")
cycle = readout.get("cycle")
if not isinstance(cycle, dict):
    sys.exit(f"/api/region has no Stokes cycle: {json.dumps(readout)}")
n = cycle["S1"]["count"]
s0 = cycle["S0"]["mean"]
s1, s2 = cycle["S1"]["mean"], cycle["S2"]["mean"]
polarized = math.hypot(s1, s2)
standard_error = math.hypot(cycle["S1"]["std"], cycle["S2"]["std"]) / math.sqrt(n)
dolp_of_mean = polarized / s0
print(f"     middle quarter ({n} pixels): S0 {s0:.1f}, S1 {s1:.2f}, S2 {s2:.2f} {cycle['S0']['units']}; "
      f"hypot(S1, S2) {polarized:.2f} = {polarized / standard_error:.1f} standard errors; "
      f"DoLP of the mean {dolp_of_mean:.5f}; mean per-pixel DoLP {cycle['DoLP']['mean']:.4f}")
if n < 100 or not polarized > 5 * standard_error or not dolp_of_mean > 1e-3:
    sys.exit("no polarization seen: hypot(mean S1, mean S2) must exceed 5 standard errors and 1e-3 of S0")
print("live check passed: polarization seen")
