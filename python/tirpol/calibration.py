"""tirpol.calibration — the bindings of tirpol::calibration (docs/python.md); help() on each function says more."""

from ._tirpol.calibration import *  # noqa: F401,F403  (the bindings are the API)
