"""Figures from results only; matplotlib is imported lazily inside each function."""

from .figure import save_figure
from .time_domain import plot_time_series

__all__ = ["plot_time_series", "save_figure"]
