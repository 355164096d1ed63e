"""Type stubs of tirpol.report (bindings of tirpol::report)."""

import os
from pathlib import Path
from typing import Any, Mapping, Optional, Sequence, Tuple, Union

import numpy.typing as npt

class Comparison:
    @property
    def statistics(self) -> dict[str, Any]: ...
    def write_html(self, report_dir: Union[str, os.PathLike[str]]) -> Path: ...

Polygon = Union[npt.ArrayLike, Sequence[Sequence[float]]]
Regions = Union[
    str,
    os.PathLike[str],
    Mapping[str, Polygon],
    Mapping[str, Any],
    Sequence[Mapping[str, Any]],
]
ControlPoints = Union[str, os.PathLike[str], npt.ArrayLike, Tuple[npt.ArrayLike, npt.ArrayLike]]

def compare(
    measured: Mapping[str, npt.ArrayLike],
    simulated: Mapping[str, npt.ArrayLike],
    registration: Optional[str] = None,
    regions: Optional[Regions] = None,
    background: Optional[str] = None,
    noise_region: Optional[str] = None,
    control_points: Optional[ControlPoints] = None,
    camera_model: Optional[Union[str, os.PathLike[str]]] = None,
    measured_frame_sigma: Optional[float] = None,
    gain_sigma: float = 0.0,
    offset_sigma: float = 0.0,
    false_alarm: float = 0.05,
    power: float = 0.80,
    band_um: Optional[Tuple[float, float]] = None,
    measured_name: str = "measured",
    simulated_name: str = "simulated",
) -> Comparison: ...
