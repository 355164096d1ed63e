"""tirpol.materials — the bindings of tirpol::materials (docs/python.md); help() on each function says more."""

from ._tirpol.materials import *  # noqa: F401,F403  (the bindings are the API)
