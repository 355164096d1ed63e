"""tirpol.acquisition — the bindings of tirpol::acquisition (docs/python.md); help() on each function says more."""

from ._tirpol.acquisition import *  # noqa: F401,F403  (the bindings are the API)
