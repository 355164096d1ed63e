"""Type stubs of tirpol.report (bindings of tirpol::report)."""

import os
from pathlib import Path
from typing import Any, Mapping, Optional, Tuple, Union

import numpy.typing as npt

class Comparison:
    @property
    def statistics(self) -> dict[str, Any]: ...
    def write_html(self, report_dir: Union[str, os.PathLike[str]]) -> Path: ...

def compare(
    measured: Mapping[str, npt.ArrayLike],
    simulated: Mapping[str, npt.ArrayLike],
    registration: str = "auto",
    measured_frame_sigma: Optional[float] = None,
    band_um: Optional[Tuple[float, float]] = None,
    measured_name: str = "measured",
    simulated_name: str = "simulated",
) -> Comparison: ...
