"""The frequency-domain side of the Wang (1971) model: linearize, modes, RAOs, equivalent linearization.

steady state (``steady_state``) -> ``linearize`` -> ``modes`` / ``rao``; for the quadratic drag
near resonance ``harmonic_response`` (regular input, describing function), ``periodic_steady_state``
(exact periodic orbit, Fourier collocation) and ``stochastic_response`` (irregular sea, Gaussian
equivalent linearization with the ``jonswap`` / ``pierson_moskowitz`` spectra).
"""

from ..lazy import lazy_exports

# public name -> module that defines it, imported on first use (cablesys.lazy)
_EXPORTS = {
    "HarmonicResponse": ".equivalent",
    "harmonic_response": ".equivalent",
    "RAO": ".frequency_response",
    "rao": ".frequency_response",
    "LinearModel": ".linearization",
    "linearize": ".linearization",
    "Modes": ".modal",
    "modes": ".modal",
    "PeriodicSolution": ".periodic",
    "periodic_steady_state": ".periodic",
    "jonswap": ".spectra",
    "pierson_moskowitz": ".spectra",
    "significant_amplitude": ".spectra",
    "slack_probability": ".spectra",
    "SteadyState": ".steady",
    "steady_state": ".steady",
    "StochasticResponse": ".stochastic",
    "stochastic_response": ".stochastic",
}

__all__ = ["RAO", "HarmonicResponse", "LinearModel", "Modes", "PeriodicSolution", "SteadyState",
           "StochasticResponse", "harmonic_response", "jonswap", "linearize", "modes", "periodic_steady_state",
           "pierson_moskowitz", "rao", "significant_amplitude", "slack_probability", "steady_state",
           "stochastic_response"]

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, __all__)
