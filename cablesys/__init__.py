"""cablesys: dynamics of suspended and towed marine cables, built on CasADi.

Data flows one way: scene description -> model (CasADi functions) -> analyses
(time domain, linear, design) -> results and plots.
"""

__version__ = "0.1.0"
