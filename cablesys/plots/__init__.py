"""Figures from results only; matplotlib is imported lazily inside each function."""

from .figure import save_figure
from .plan import plot_plan_view
from .time_domain import plot_time_series

__all__ = ["plot_plan_view", "plot_time_series", "save_figure"]
