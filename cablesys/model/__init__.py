"""The equations, written once: energies + generalized forces -> CasADi functions."""

from .build import build_model
from .cable_model import CableModel, FunctionCache
from .params import ParameterLayout, parameter_items, structure_of
from .signals import EXO_LABELS, OUTPUT_NAMES

__all__ = ["CableModel", "EXO_LABELS", "FunctionCache", "OUTPUT_NAMES", "ParameterLayout", "build_model",
           "parameter_items", "structure_of"]
