"""Scene description: immutable, validated parameter objects in SI, TOML in and out."""

from .components import INTEGRATORS, Body, Cable, Environment, Initial, Numerics, Section, TimeSeries, TopMotion
from .ends import Anchor, Leg, Seabed, Winch
from .harmonics import Sinusoid, Wave
from .dale import OMEGA_N_MEASURED, dale_scene, default_scene
from .heavy_wire import heavy_wire_scene
from .scene import Scene, single_section_scene
from .system import Line, Point, System
from .toml_io import dump_scene, load_scene, scene_from_dict

__all__ = ["Anchor", "Body", "Seabed", "Cable", "Environment", "Initial", "INTEGRATORS", "Line", "Numerics", "Point",
           "Scene", "Section", "System",
           "Sinusoid", "TimeSeries", "TopMotion", "Wave", "Winch", "Leg", "OMEGA_N_MEASURED", "dale_scene",
           "default_scene", "dump_scene", "heavy_wire_scene", "load_scene", "scene_from_dict", "single_section_scene"]
