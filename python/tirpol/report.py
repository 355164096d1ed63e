"""tirpol.report — the bindings of tirpol::report (docs/python.md); help() on each function says more."""

from ._tirpol.report import *  # noqa: F401,F403  (the bindings are the API)
