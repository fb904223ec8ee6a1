"""A full-scale dual-isolation example: an instrument package lowered from a ship in a sea.

Values are typical catalogue and textbook numbers (stated per item); they make a realistic
example, not a particular vessel or rope.

* Package: 300 kg dry, 0.1 m^3 displaced (an instrument frame): weight in water
  W = (300 - 1025 x 0.1) g = 1937 N, virtual mass 300 + C_a rho V with C_a = 1 (a bluff frame),
  C_D A = 0.8 m^2 in every direction (sphere law, eq. 32).
* Intermediate body: a heave-damper plate with clump, 400 kg of steel on a 1.6 m disk:
  weight in water 400 g (1 - 1025 / 7850) = 3414 N; heave added mass of a disk rho D^3 / 3
  = 1400 kg (DNV-RP-H103 Table A-2), so M_bvy = 1800 kg, M_bvx = 420 kg (edge-on);
  drag areas (C_D A)_t = 2.0 x 2.0 m^2 along the vertical axis, (C_D A)_n = 0.2 m^2 (eq. 33-35).
* Rope: 20 mm synthetic rope, 0.27 kg/m in air, 0.68 N/m in water (polyester, density
  1380 kg/m^3), C_D = 1.2, C_t = 0.01; 150 m ship-to-plate, 50 m plate-to-package.
  Baseline: one 200 m polyester rope, AE = 1.5 MN, C_I = 1e5 N s, straight to the package.
* Sea: JONSWAP Hs = 2.5 m, Tp = 9 s, gamma = 3.3; the top follows the surface orbit.

Design bounds (practical rope ranges at this size):
* AE in [0.15, 3] MN: the effective (working-load) stiffness of a 20 mm rope runs from
  about 2 x MBL for nylon (MBL ~ 75 kN; nylon's quasi-static EA/MBL is 2-5 at low loads)
  to about 20-40 x MBL for polyester (1.5-3 MN).
* C_I in [5e3, 5e5] N s: a Voigt damper C_I = tan(delta) AE / omega with loss tangents
  tan(delta) of 0.02-0.2 for nylon and polyester ropes at wave frequencies (0.5-1.5 rad/s)
  spans ~3e3 to ~1e6 N s over the AE range; the upper end is also reachable with an in-line
  snubber/damper.
* Limits: static strain 10 % (a nylon rope's working strain at ~20 % MBL), working load
  15 kN (MBL / 5), no slack at 3 standard deviations.
"""

from __future__ import annotations

import math

from .. import units as U
from ..scene import Body, Cable, Environment, Numerics, Scene, Section
from .problem import DesignSettings

RHO, G = U.RHO_SEA, U.G_STANDARD
ROPE = dict(diameter=0.02, mass_per_length=0.27, weight_per_length=0.68, cd_normal=1.2, ct_tangential=0.01)
PACKAGE = dict(dry_mass=300.0, volume=0.1, added_mass_coef=1.0, drag_area=0.8)
PLATE = dict(dry_mass=400.0, steel_density=7850.0, diameter=1.6, cd_axial=2.0, cda_edge=0.2)
LENGTHS = (150.0, 50.0)


def package_body() -> Body:
    m, vol = PACKAGE["dry_mass"], PACKAGE["volume"]
    mv = m + PACKAGE["added_mass_coef"] * RHO * vol
    return Body(weight=(m - RHO * vol) * G, mass_x=mv, mass_y=mv,
                drag_area_normal=PACKAGE["drag_area"], drag_area_tangential=PACKAGE["drag_area"])


def plate_body() -> Body:
    m, d = PLATE["dry_mass"], PLATE["diameter"]
    added_heave = RHO * d**3 / 3.0                    # disk in heave, DNV-RP-H103 Table A-2
    return Body(weight=m * G * (1 - RHO / PLATE["steel_density"]), mass_x=m + 20.0, mass_y=m + added_heave,
                drag_area_normal=PLATE["cda_edge"], drag_area_tangential=PLATE["cd_axial"] * math.pi / 4 * d**2,
                axis_angle_deg=0.0)


def _rope(length: float, tension: float, ae: float, c_i: float) -> Cable:
    return Cable(length=length, tension_ref=tension, ae=ae, internal_damping=c_i, **ROPE)


def baseline_scene(*, duration: float = 600.0) -> Scene:
    """One 200 m polyester rope from the ship straight to the package."""
    pkg = package_body()
    length = sum(LENGTHS)
    t_ref = pkg.weight + 0.5 * ROPE["weight_per_length"] * length
    return Scene(name="baseline: 200 m polyester rope, 300 kg package",
                 sections=(Section(cable=_rope(length, t_ref, 1.5e6, 1e5), body=pkg),),
                 environment=Environment(density=RHO, gravity=G),
                 numerics=Numerics(duration=duration, output_step=0.25, drag_segments=6, rtol=1e-6, atol=1e-8))


def dual_scene(*, ae=(1.5e6, 1.5e6), c_i=(1e5, 1e5), duration: float = 600.0) -> Scene:
    """Ship - 150 m rope - damper plate - 50 m rope - package (the report's dual isolation, shared angle).

    Each rope's reference tension is its mean hanging tension, so ``length`` is the deployed
    length whatever AE the design picks (eq. 1)."""
    pkg, plate = package_body(), plate_body()
    w = ROPE["weight_per_length"]
    t2 = pkg.weight + 0.5 * w * LENGTHS[1]
    t1 = pkg.weight + w * LENGTHS[1] + plate.weight + 0.5 * w * LENGTHS[0]
    return Scene(name="dual isolation: 150 m rope, damper plate, 50 m rope, 300 kg package", angles="shared",
                 sections=(Section(cable=_rope(LENGTHS[0], t1, ae[0], c_i[0]), body=plate),
                           Section(cable=_rope(LENGTHS[1], t2, ae[1], c_i[1]), body=pkg)),
                 environment=Environment(density=RHO, gravity=G),
                 numerics=Numerics(duration=duration, output_step=0.25, drag_segments=6, rtol=1e-6, atol=1e-8))


def example_settings(**changes) -> DesignSettings:
    base = dict(ae_bounds=((3e4, 3e6), (3e4, 3e6)), damping_bounds=((5e3, 5e5), (5e3, 5e5)),
                hs=2.5, tp=9.0, gamma=3.3, omega_min=0.25, omega_max=3.0, n_omega=60,
                strain_limit=(0.10, 0.10), working_load=(1.5e4, 1.5e4), n_sigma=3.0, n_starts=4)
    base.update(changes)
    return DesignSettings(**base)


def design_template(scene=None) -> str:
    """A commented ``[design]`` table for ``cablesys scene --example --design``, sized to ``scene``
    (default: the Dale scene): AE bounds 0.1-10 x the scene's AE (above 2 x its reference tension),
    C_I bounds 1e-4-0.1 s x AE, working load 5 x the static top tension, and the scene's sea, or a
    sea scaled to it (Hs = 5 % of the cable length up to 2.5 m, Tp the forcing period)."""
    import math

    from ..scene import default_scene
    scene = scene or default_scene()
    secs = scene.sections
    n = len(secs)
    below, top_tension = 0.0, []
    for s in reversed(secs):
        below += s.body.weight + s.cable.total_weight
        top_tension.insert(0, below)
    sea = scene.top_motion.spectrum
    freqs = [t.frequency for t in scene.top_motion.x + scene.top_motion.y]
    if sea is not None:
        hs, tp, gamma = sea.hs, sea.tp, sea.gamma
    else:
        hs = min(2.5, 0.05 * sum(s.cable.length for s in secs))
        tp = 2 * math.pi / min(freqs) if freqs else 8.0
        gamma = 3.3
    wp = 2 * math.pi / tp

    def pairs(f):
        return "[" + ", ".join(f"[{a:.3g}, {b:.3g}]" for a, b in (f(s) for s in secs)) + "]"

    ae = pairs(lambda s: (max(0.1 * s.cable.ae, 2 * s.cable.tension_ref), 10 * s.cable.ae))
    ci = pairs(lambda s: (1e-4 * s.cable.ae, 0.1 * s.cable.ae))
    wl = "[" + ", ".join(f"{5 * t:.4g}" for t in top_tension) + "]"
    lines = [
        "",
        "# ---- isolation design: `cablesys design this.toml --out design/` --------------------------",
        "# Minimizes the lower body's heave in the sea below over each section's AE and C_I within the",
        "# bounds, with no-slack, working-load and static-strain constraints (Wang 1971 p. 33; IPOPT).",
        "# Writes design.json and figures (RAOs before/after, objective history, constraint margins).",
        "[design]",
        f"ae_bounds = {ae}   # [N] (AE)_r of each section, [lower, upper], top first",
        f"damping_bounds = {ci}   # [N s] Voigt damping C_I of each section (eq. 46)",
        'objective = "significant"   # significant: 2 sigma of y_b in the sea | rao_band: mean |y_b/y_s| over band',
        f"hs = {hs:.4g}   # [m] JONSWAP significant wave height (default: the scene's [top_motion.spectrum])",
        f"tp = {tp:.4g}   # [s] peak period",
        f"gamma = {gamma:g}   # peak enhancement (1: Pierson-Moskowitz)",
        f"omega_min = {0.3 * wp:.3g}   # [rad/s] frequency grid of the spectral integrals",
        f"omega_max = {4 * wp:.3g}",
        "n_omega = 60",
        f"band = [{0.6 * wp:.3g}, {1.6 * wp:.3g}]   # [rad/s] band of the rao_band objective",
        f"strain_limit = [{', '.join(['0.1'] * n)}]   # static stretch u_0 / l_0 of each section",
        f"working_load = {wl}   # [N] mean + n_sigma std of the tension of each section (5 x static here)",
        "n_sigma = 3.0   # slack: mean - n_sigma std > tension floor; peak: mean + n_sigma std < working load",
        "n_starts = 4   # IPOPT starts (the scene's values + a Latin hypercube)",
        "outer_iterations = 6   # passes of the drag-linearization fixed point",
        "max_iter = 300   # IPOPT iterations per start",
        "tol = 1e-8   # IPOPT tolerance",
        "# intermediate_mass_bounds = [500.0, 3000.0]   # [kg] also tune body 1's heave virtual mass (dual isolation)",
    ]
    return "\n".join(lines) + "\n"
