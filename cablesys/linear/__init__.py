"""Steady state, linearization, natural frequencies and RAOs (the frequency-domain side)."""

from .steady import SteadyState, steady_state

__all__ = ["SteadyState", "steady_state"]
