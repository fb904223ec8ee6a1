"""The dual-isolation design NLP (Wang 1971 p. 33): tune AE and C_I per section with IPOPT."""

from .problem import DesignSettings, settings_from_dict, settings_to_toml, variables
from .results import DesignResult
from .solve import DesignInfeasible, design

__all__ = ["DesignInfeasible", "DesignResult", "DesignSettings", "design", "settings_from_dict", "settings_to_toml", "variables"]
