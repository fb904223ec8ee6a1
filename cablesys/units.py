"""Unit conversions: one place for every factor. SI inside; convert at the edges.

Wang (1971) and Dale et al. work in ft, lb (force), slug; Kennedy & Strahan (1981) in SI.
"""

FT = 0.3048                      # m per ft (exact)
INCH = 0.0254                    # m per inch (exact)
LBF = 4.4482216152605            # N per lbf (exact)
SLUG = LBF / FT                  # kg per slug (1 lbf s^2/ft) = 14.5939...
KNOT = 1852.0 / 3600.0           # m/s per knot (exact)
G_STANDARD = 9.80665             # m/s^2, standard gravity
RHO_FRESH = 1000.0               # kg/m^3, fresh water (Dale et al. water channel)
RHO_SEA = 1025.0                 # kg/m^3, sea water

# factor to SI for each unit name used in scene files
TO_SI = {
    "m": 1.0, "ft": FT, "in": INCH,
    "N": 1.0, "lb": LBF, "lbf": LBF,
    "kg": 1.0, "slug": SLUG,
    "s": 1.0, "rad": 1.0,
    "knot": KNOT,
}

UNIT_SYSTEMS = ("SI", "fps")

# output units: SI unit -> (factor multiplying the SI value, unit name) in the report's ft/lb/slug system
FPS_OUT = {
    "m": (1 / FT, "ft"), "N": (1 / LBF, "lbf"), "m/s": (1 / FT, "ft/s"), "m/s^2": (1 / FT, "ft/s^2"),
    "kg": (1 / SLUG, "slug"), "N/m": (FT / LBF, "lbf/ft"), "m^2": (1 / FT**2, "ft^2"), "N s": (1 / LBF, "lbf s"),
    "m/m": (1.0, "ft/ft"), "N^2 s/rad": (1 / LBF**2, "lbf^2 s/rad"), "m^2 s/rad": (1 / FT**2, "ft^2 s/rad"),
}


def output_unit(si_unit: str, system: str = "SI") -> tuple[float, str]:
    """(factor, unit name) to show an SI quantity in ``system``: shown value = SI value x factor.

    Parameters
    ----------
    si_unit : str
        The SI unit of the quantity ("m", "N", "rad", "-", ...).
    system : str
        "SI" or "fps" (ft, lbf, slug, s; angles stay in rad).

    Returns
    -------
    tuple of (float, str)
        Units without an fps counterpart (rad, s, rad/s, dimensionless) keep factor 1.
    """
    if system == "fps" and si_unit in FPS_OUT:
        return FPS_OUT[si_unit]
    return 1.0, si_unit


def per_input_unit(si_output_unit: str, system: str = "SI", si_input_unit: str = "m") -> tuple[float, str]:
    """(factor, unit name) of a response per unit top motion (SI: unit/m; per unit of a vessel's rotation,
    ``si_input_unit`` "rad": unit/rad in both systems) shown in ``system``."""
    f, name = output_unit(si_output_unit, system)
    if si_input_unit == "rad":
        return f, f"{name or '-'}/rad"
    if system == "fps":
        return f * FT, f"{name or '-'}/ft"
    return f, f"{name or '-'}/m"
