"""The worked examples of docs/python.md run as written: each ```python block that starts with
'# example: <name>' is executed from the source root (so its relative paths are the README's) with
the Agg backend, writing into a temporary folder."""

import json
import os
import re
import runpy

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")


def examples(source_dir):
    text = (source_dir / "docs" / "python.md").read_text(encoding="utf-8")
    return dict(re.findall(r"```python\n# example: (\S+)\n(.*?)```", text, flags=re.S))


def run_example(source_dir, tmp_path, name):
    code = examples(source_dir)[name]
    script = tmp_path / f"{name}.py"
    script.write_text(code.replace('"config/', f'"{source_dir}/config/'), encoding="utf-8")
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        return runpy.run_path(str(script))
    finally:
        os.chdir(cwd)


def test_the_page_has_every_example(source_dir):
    assert set(examples(source_dir)) == {"ball_on_snow_figure", "reduce_arrays", "session_and_fit",
                                         "capture_with_progress"}


def test_ball_on_snow_figure(source_dir, tmp_path, monkeypatch):
    monkeypatch.setenv("TIRPOL_CACHE_DIR", str(tmp_path / "cache"))
    result = run_example(source_dir, tmp_path, "ball_on_snow_figure")
    assert (tmp_path / "ball_on_snow_day_stokes.png").stat().st_size > 10_000
    image = result["image"]
    assert image["S1"].shape == (128, 160)


def test_reduce_arrays(source_dir, tmp_path):
    result = run_example(source_dir, tmp_path, "reduce_arrays")
    stokes = result["stokes"]
    assert float((stokes["S1"] / stokes["S0"]).mean()) == pytest.approx(-0.02, abs=1e-4)
    assert (tmp_path / "reduced.exr").exists()


def test_session_and_fit(source_dir, tmp_path):
    result = run_example(source_dir, tmp_path, "session_and_fit")
    s1, truth = result["s1"], result["truth"]["S1"][result["panel"]]
    assert abs(s1.mean() - truth.mean()) < 4 * 0.04 / np.sqrt(s1.size)  # as test_calibration_sessions
    fit = result["fit"]
    assert fit.usable and fit.free_names == ["n", "sigma"]
    for name, truth_value in (("n", 1.6), ("sigma", 0.35)):  # config/materials/flat_black_paint.yaml
        assert abs(fit.estimates[name] - truth_value) < 3 * fit.sigmas[name]


def test_capture_with_progress(source_dir, tmp_path, capsys):
    result = run_example(source_dir, tmp_path, "capture_with_progress")
    assert result["summary"]["steps_recorded"] == 4 and result["summary"]["frames"] == 32
    printed = capsys.readouterr().out.splitlines()
    assert printed[:4] == [f"{i}/4: polarizer {a}° -> frames/s{i - 1:03d}_pol_{a:07.3f}deg_r0.exr"
                           for i, a in zip(range(1, 5), (0, 45, 90, 135))]
    manifest = json.loads((tmp_path / "capture" / "session.json").read_text(encoding="utf-8"))
    assert manifest["complete"] and len(manifest["records"]) == 4
