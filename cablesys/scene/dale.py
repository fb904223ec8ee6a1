"""The built-in default scene: the Dale et al. water-channel model (Wang 1971, Table 1 and p. 29-30).

Inputs from the report: 9 ft cable of 0.025 in diameter, total weight in water 0.0036 lb and
total mass 0.000171 slug; a 1 in sphere of submerged weight 0.025 lb; circular top motion of
5 in peak to peak; zero current; internal damping 0; AE "between 5 and 1000 lb" (we take
1000 lb, the report's estimate for a cable half steel by area).

Our choices (the report does not print them), with reasons:
- fresh water, rho = 1000 kg/m^3 (a circulating water channel);
- body virtual masses: dry mass W/g + rho V plus the added mass of a sphere, rho V / 2;
- sphere drag C_D = 0.5: the steady-flow sphere curve gives 0.40-0.47 at the Reynolds numbers
  reached here (Re = 1e3-5e3), oscillatory flow at Keulegan-Carpenter numbers of 10-30 raises it;
- cable normal drag C_D = 1.4 (circular cylinder at Re ~ 50-150), tangential C_t = 0.01;
- reference tension T_r = W_b + W_c/2, the mean hanging tension, so that 9 ft is the loaded length.
"""

from __future__ import annotations

import math

from .. import units as U
from .components import Body, Cable, Environment, Numerics, TopMotion
from .harmonics import Sinusoid
from .scene import Scene, single_section_scene

OMEGA_N_MEASURED = 1.14          # rad/s, Dale et al. measured horizontal natural frequency (Table 1)
TOP_MOTION_PEAK_TO_PEAK = 5.0 * U.INCH
SPHERE_CD = 0.5
CABLE_CD = 1.4
CABLE_CT = 0.01


def dale_scene(*, omega_ratio: float = 1.0, ae_lb: float = 1000.0, duration: float = 120.0,
               output_step: float = 0.05) -> Scene:
    """The Dale et al. model scene driven in a circle at ``omega_ratio * 1.14`` rad/s.

    Parameters
    ----------
    omega_ratio : float, optional
        Forcing frequency over the measured natural frequency 1.14 rad/s (Wang 1971 Table 1).
    ae_lb : float, optional
        Axial stiffness AE in lb (the report: "between 5 and 1000 lb").
    duration : float, optional
        Simulated time (s).
    output_step : float, optional
        Output interval (s).

    Returns
    -------
    Scene
        One section: 9 ft cable, 1 in sphere, circular top motion of 5 in peak to peak.
    """
    rho, g = U.RHO_FRESH, U.G_STANDARD
    length = 9.0 * U.FT
    w_c = 0.0036 * U.LBF                       # total cable weight in water
    m_c = 0.000171 * U.SLUG                    # total cable mass
    d_b = 1.0 * U.INCH
    w_b = 0.025 * U.LBF
    vol = math.pi / 6.0 * d_b**3
    m_b = w_b / g + rho * vol                  # dry mass of the sphere
    m_virtual = m_b + 0.5 * rho * vol          # plus the added mass of a sphere
    area = math.pi / 4.0 * d_b**2
    cable = Cable(length=length, tension_ref=w_b + 0.5 * w_c, ae=ae_lb * U.LBF,
                  diameter=0.025 * U.INCH, mass_per_length=m_c / length,
                  weight_per_length=w_c / length, thinning_ratio=0.0, added_mass_factor=1.0,
                  cd_normal=CABLE_CD, ct_tangential=CABLE_CT, internal_damping=0.0, tension_floor=0.0)
    body = Body(weight=w_b, mass_x=m_virtual, mass_y=m_virtual,
                drag_area_normal=SPHERE_CD * area, drag_area_tangential=SPHERE_CD * area,
                axis_angle_deg=999.0)
    omega = omega_ratio * OMEGA_N_MEASURED
    a = 0.5 * TOP_MOTION_PEAK_TO_PEAK
    top = TopMotion(x=(Sinusoid(amplitude=a, frequency=omega, phase=math.pi / 2),),   # a cos(wt)
                    y=(Sinusoid(amplitude=a, frequency=omega, phase=0.0),),           # a sin(wt)
                    ramp_s=0.0)    # Wang's runs start abruptly from rest (his Tables 2-3 are checked against it)
    return single_section_scene(
        cable=cable, body=body, name=f"Dale et al. water-channel model, omega/omega_n = {omega_ratio:g}",
        environment=Environment(density=rho, gravity=g),
        top_motion=top, numerics=Numerics(duration=duration, output_step=output_step, drag_segments=10))


def default_scene() -> Scene:
    """The built-in default scene (Dale et al. at omega = omega_n).

    Returns
    -------
    Scene
        :func:`dale_scene` with its defaults.
    """
    return dale_scene()
