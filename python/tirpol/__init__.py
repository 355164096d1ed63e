"""tirpol — thermal-infrared polarimetry from Python.

The C++ toolkit's libraries with numpy arrays in and out (docs/python.md):

- ``tirpol.core``: Stokes/Mueller helpers, Planck band radiance and brightness temperature, EXR files.
- ``tirpol.materials``: material files, polarized directional emissivity, the Mueller pBRDF on arrays.
- ``tirpol.simulation``: scenes from YAML files or dicts, the polarized path tracer.
- ``tirpol.calibration``: the analyzer model and Stokes reduction with uncertainties.
- ``tirpol.fitting``: Ceres fits of micro-facet pBRDF parameters with covariance and 2σ intervals.
- ``tirpol.report``: measured-vs-simulated comparison statistics as a dict, the HTML report.
- ``tirpol.acquisition``: cameras opened by URI (the fake GigE Vision camera, ``sim://``), frames as arrays.

Images are :class:`tirpol.Image`: a dict of channel name → float32 array of shape (H, W), with the
EXR header attributes in ``.attributes``. Errors from the C++ library raise :class:`tirpol.Error`
(a ``RuntimeError``) with the library's message; long calls release the GIL and stop on Ctrl-C.
"""

from ._tirpol import Cancelled, DeviceError, Error
from .image import Image
from . import acquisition, calibration, core, fitting, materials, report, simulation

__all__ = [
    "Cancelled", "DeviceError", "Error", "Image", "acquisition", "calibration", "core", "fitting", "materials",
    "report", "simulation",
]
