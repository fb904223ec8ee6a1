"""Figures from results only; matplotlib is imported lazily inside each function."""
