"""The frequency-domain side of the Wang (1971) model: linearize, modes, RAOs, equivalent linearization.

steady state (``steady_state``) -> ``linearize`` -> ``modes`` / ``rao``; for the quadratic drag
near resonance ``harmonic_response`` (regular input, describing function), ``periodic_steady_state``
(exact periodic orbit, Fourier collocation) and ``stochastic_response`` (irregular sea, Gaussian
equivalent linearization with the ``jonswap`` / ``pierson_moskowitz`` spectra).
"""

from .equivalent import HarmonicResponse, harmonic_response
from .frequency_response import RAO, rao
from .linearization import LinearModel, linearize
from .modal import Modes, modes
from .periodic import PeriodicSolution, periodic_steady_state
from .spectra import (
           jonswap,
           pierson_moskowitz,
           significant_amplitude,
           slack_probability,
)
from .steady import SteadyState, steady_state
from .stochastic import StochasticResponse, stochastic_response

__all__ = ["RAO", "HarmonicResponse", "LinearModel", "Modes", "PeriodicSolution", "SteadyState",
           "StochasticResponse", "harmonic_response", "jonswap", "linearize", "modes", "periodic_steady_state",
           "pierson_moskowitz", "rao", "significant_amplitude", "slack_probability", "steady_state",
           "stochastic_response"]
