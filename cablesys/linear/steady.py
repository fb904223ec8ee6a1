"""Moved to :mod:`cablesys.statics.steady` (the layer below both simulate and linear); kept as a re-export."""

from ..statics.steady import SteadyState, static_residual, steady_state  # noqa: F401

__all__ = ["SteadyState", "static_residual", "steady_state"]
