"""The dual-isolation design NLP (Wang 1971 p. 33): tune AE and C_I per section with IPOPT."""

from ..lazy import lazy_exports

# public name -> module that defines it, imported on first use (cablesys.lazy)
_EXPORTS = {
    "DesignSettings": ".problem",
    "settings_from_dict": ".problem",
    "settings_to_toml": ".problem",
    "variables": ".problem",
    "DesignResult": ".results",
    "DesignInfeasible": ".solve",
    "design": ".solve",
}

__all__ = ["DesignInfeasible", "DesignResult", "DesignSettings", "design", "settings_from_dict", "settings_to_toml", "variables"]

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, __all__)
