"""Type stubs of tirpol.calibration (bindings of tirpol::calibration)."""

from typing import Mapping, Optional, Sequence

import numpy as np
import numpy.typing as npt

from .image import Image

class AnalyzerPosition:
    @property
    def nominal_angle_deg(self) -> float: ...
    @property
    def axis_angle_deg(self) -> float: ...
    @property
    def diattenuation(self) -> float: ...
    @property
    def relative_transmission(self) -> float: ...
    @property
    def background(self) -> float: ...
    @property
    def extinction_ratio(self) -> float: ...

class AnalyzerModel:
    @staticmethod
    def ideal(angles_deg: Sequence[float]) -> AnalyzerModel: ...
    @staticmethod
    def non_ideal(
        angles_deg: Sequence[float], extinction_ratio: float, angle_offset_deg: float = 0.0, t_max: float = 1.0
    ) -> AnalyzerModel: ...
    @property
    def positions(self) -> list[AnalyzerPosition]: ...
    def data_reduction_matrix(self) -> npt.NDArray[np.float64]: ...
    def condition_number(self) -> float: ...

def reduce(
    images: Mapping[float, npt.ArrayLike],
    stds: Optional[Mapping[float, npt.ArrayLike]] = None,
    model: Optional[AnalyzerModel] = None,
    project_to_realizable: bool = True,
    include_slar: bool = False,
    units: str = "W/(m^2 sr)",
) -> Image: ...
