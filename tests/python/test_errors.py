"""C++ errors arrive as tirpol.Error (a RuntimeError) with the library's message; bad input from
Python (shapes, attribute types) gets the same kind of message, and nothing is written."""

import numpy as np
import pytest

import tirpol
from tirpol import core, simulation


def test_error_types_form_a_hierarchy():
    assert issubclass(tirpol.Error, RuntimeError)
    assert issubclass(tirpol.Cancelled, tirpol.Error)


def test_missing_exr_names_the_file(tmp_path):
    missing = tmp_path / "no_such.exr"
    with pytest.raises(tirpol.Error, match="no_such.exr"):
        core.read_exr(missing)


def test_corrupt_exr_names_the_file(tmp_path):
    bad = tmp_path / "truncated.exr"
    bad.write_bytes(b"\x76\x2f\x31\x01" + b"\0" * 10)  # EXR magic, then nothing
    with pytest.raises(tirpol.Error, match="truncated.exr"):
        core.read_exr(bad)


def test_bad_arrays_and_attributes_are_rejected_before_writing(tmp_path):
    path = tmp_path / "out.exr"
    with pytest.raises(tirpol.Error, match=r"channel 'S1': shape \(3, 4\) differs from the first array's \(2, 2\)"):
        core.write_exr(path, {"S0": np.zeros((2, 2)), "S1": np.zeros((3, 4))})
    with pytest.raises(tirpol.Error, match="attribute 'flag': .* got a bool"):
        core.write_exr(path, {"S0": np.zeros((2, 2))}, {"flag": True})
    with pytest.raises(tirpol.Error, match="expected a 2-D array"):
        core.write_exr(path, {"S0": np.zeros(4)})
    assert not path.exists()


def test_scene_dict_errors_are_the_loaders_messages(source_dir, tmp_path):
    scene = {"band": {"lo_um": 8, "hi_um": 14}, "camra": {}, "objects": []}
    with pytest.raises(tirpol.Error) as from_dict:
        simulation.scene_from_dict(scene, base_dir=source_dir / "config" / "scenes")
    # The same typo in a YAML file: the same message apart from where the text came from.
    path = tmp_path / "typo.yaml"
    path.write_text("band: {lo_um: 8, hi_um: 14}\ncamra: {}\nobjects: []\n")
    with pytest.raises(tirpol.Error) as from_file:
        simulation.load_scene(path)
    assert "camra" in str(from_dict.value) and "camera" in str(from_dict.value)
    tail = lambda e: str(e.value).split(": ", 1)[1]  # noqa: E731  (drop "file:line:col")
    assert tail(from_dict) == tail(from_file)
