"""tirpol.simulation — the bindings of tirpol::simulation (docs/python.md); help() on each function says more."""

from ._tirpol.simulation import *  # noqa: F401,F403  (the bindings are the API)
