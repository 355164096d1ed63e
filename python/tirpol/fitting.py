"""tirpol.fitting — the bindings of tirpol::fitting (docs/python.md); help() on each function says more."""

from ._tirpol.fitting import *  # noqa: F401,F403  (the bindings are the API)
