"""Type stubs of tirpol.fitting (bindings of tirpol::fitting)."""

from typing import Any, Mapping, Optional, Sequence, Tuple

import numpy as np
import numpy.typing as npt

from .simulation import Scene

class FitResult:
    @property
    def estimates(self) -> dict[str, float]: ...
    @property
    def sigmas(self) -> dict[str, float]: ...
    @property
    def intervals_2sigma(self) -> dict[str, Tuple[float, float]]: ...
    @property
    def free_names(self) -> list[str]: ...
    @property
    def covariance(self) -> npt.NDArray[np.float64]: ...
    @property
    def correlation(self) -> npt.NDArray[np.float64]: ...
    @property
    def covariance_available(self) -> bool: ...
    @property
    def at_bound(self) -> list[str]: ...
    @property
    def chi2(self) -> float: ...
    @property
    def dof(self) -> int: ...
    @property
    def reduced_chi2(self) -> float: ...
    @property
    def usable(self) -> bool: ...
    @property
    def termination(self) -> str: ...
    @property
    def warnings(self) -> list[str]: ...
    @property
    def model_e_s0(self) -> list[float]: ...
    @property
    def model_e_s1(self) -> list[float]: ...

def fit_microfacet(
    angle_deg: npt.ArrayLike,
    e_s0: npt.ArrayLike,
    e_s0_sigma: npt.ArrayLike,
    e_s1: npt.ArrayLike,
    e_s1_sigma: npt.ArrayLike,
    wavelength_um: float = 10.0,
    parameters: Mapping[str, Mapping[str, float | bool]] = ...,
    starts: int = 16,
    seed: int = 1,
    scale_covariance_by_reduced_chi2: bool = False,
) -> FitResult: ...
def fit_microfacet_joint(
    datasets: Sequence[Mapping[str, npt.ArrayLike | float]],
    parameters: Mapping[str, Mapping[str, float | bool]] = ...,
    starts: int = 16,
    seed: int = 1,
    scale_covariance_by_reduced_chi2: bool = False,
) -> FitResult: ...
def fit_through_renderer(
    scene: Scene,
    views: Sequence[Mapping[str, Any]],
    parameters: Sequence[Mapping[str, Any]],
    stokes: Sequence[int] = ...,
    pixels: bool = False,
    samples_per_pixel: int = 0,
    seed: Optional[int] = None,
    forward: bool = False,
    max_iterations: int = 20,
    threads: int = 0,
) -> dict[str, Any]: ...
