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
