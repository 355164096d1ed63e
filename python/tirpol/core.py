"""tirpol.core — the bindings of tirpol::core (docs/python.md); help() on each function says more."""

from ._tirpol.core import *  # noqa: F401,F403  (the bindings are the API)
