"""A long heavy cable: 1000 m of steel wire rope holding a 300 kg instrument sphere (model-ladder study scene
``heavy1000``, the heavy cable of studies/segments_convergence.py).

Rope (typical 16 mm 6x36 IWRC catalogue values): 1.1 kg/m in air, 9.4 N/m in sea water, metallic area
1.2e-4 m^2 x E = 1.0e11 Pa -> AE = 1.2e7 N, normal drag C_D = 1.2, tangential C_t = 0.01. Sphere of 0.5 m
diameter, 300 kg dry: weight in water 300 g - rho g V, virtual mass with the sphere's added mass rho V / 2,
C_D = 0.5. The cable weighs about four times the body in water, the case where one straight element degrades;
a 10 s period forces it at 2.7x its first string mode, where the transverse wave is drag-controlled.
"""

from __future__ import annotations

import math

from .. import units as U
from .components import Body, Cable, Environment, Numerics, TopMotion
from .harmonics import Sinusoid
from .scene import Scene, single_section_scene

LENGTH = 1000.0                 # m
WEIGHT_PER_LENGTH = 9.4         # N/m in sea water
MASS_PER_LENGTH = 1.1           # kg/m
AE = 1.2e7                      # N
SPHERE_DIAMETER, SPHERE_MASS, SPHERE_CD = 0.5, 300.0, 0.5


def heavy_wire_scene(*, period: float | None = 10.0, amplitude: float = 1.0, duration: float = 120.0,
                     output_step: float = 0.1) -> Scene:
    """The 1000 m wire and 300 kg sphere, its top moved in a circle (surge and heave) of ``amplitude``.

    Parameters
    ----------
    period : float or None, optional
        Period of the top motion (s); None: the top does not move.
    amplitude : float, optional
        Surge and heave amplitude of the top (m).
    duration, output_step : float, optional
        Simulated time and output interval (s): 120 s lets the surge settle (30 s smooth start plus 14.7 s for
        the transverse wave to run down the hanging wire, :func:`cablesys.ladder.estimate.settling_time`).

    Returns
    -------
    Scene
        One section in sea water, 10 drag points.
    """
    rho, g = U.RHO_SEA, U.G_STANDARD
    vol = math.pi / 6 * SPHERE_DIAMETER**3
    w_b = SPHERE_MASS * g - rho * g * vol
    area = math.pi / 4 * SPHERE_DIAMETER**2
    cable = Cable(length=LENGTH, tension_ref=w_b + 0.5 * WEIGHT_PER_LENGTH * LENGTH, ae=AE, diameter=0.016,
                  mass_per_length=MASS_PER_LENGTH, weight_per_length=WEIGHT_PER_LENGTH, cd_normal=1.2,
                  ct_tangential=0.01)
    m_v = SPHERE_MASS + 0.5 * rho * vol
    body = Body(weight=w_b, mass_x=m_v, mass_y=m_v, drag_area_normal=SPHERE_CD * area,
                drag_area_tangential=SPHERE_CD * area)
    name = "1000 m steel wire, 300 kg sphere"
    top = TopMotion()
    if period is not None:
        w = 2 * math.pi / period
        top = TopMotion(x=(Sinusoid(amplitude=amplitude, frequency=w, phase=math.pi / 2),),
                        y=(Sinusoid(amplitude=amplitude, frequency=w),))
        name += f", T = {period:g} s"
    return single_section_scene(cable=cable, body=body, name=name, environment=Environment(density=rho, gravity=g),
                                top_motion=top, numerics=Numerics(duration=duration, output_step=output_step,
                                                                  drag_segments=10))
