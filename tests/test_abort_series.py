"""Regression: a sampled top-motion series with slack used to abort the process (issue 9).

Root cause (see cablesys/model/top_motion.py): CasADi's degree-0 B-spline evaluation (the third
time derivative of the MX ``bspline`` top motion, needed by the slack-event locator) wrote one
double before its work vector when evaluated exactly at an interior knot. The run is done in a
subprocess so that a heap corruption fails this test instead of killing pytest.
"""

import json
import subprocess
import sys
import textwrap

import pytest

SCRIPT = textwrap.dedent("""
    import json, math
    import numpy as np
    from cablesys.scene import (Body, Cable, Environment, Numerics, Sinusoid, TimeSeries, TopMotion,
                                single_section_scene)
    from cablesys.time_domain import simulate

    # 300 m steel wire (25 mm, AE 4e7 N, 2.5 kg/m) with a 2 t sphere (1.6 m); 1 m heave at T = 6 s
    # goes slack each cycle. The 305-sample all-zero series puts interior spline knots on output times
    # (7.5 s = sample 38 = output 75).
    cable = Cable(length=300.0, tension_ref=3000.0, ae=4.0e7, diameter=0.025, mass_per_length=2.5,
                  weight_per_length=19.6, cd_normal=1.2, ct_tangential=0.01, tension_floor=0.0)
    body = Body(weight=1000.0, mass_x=3100.0, mass_y=3100.0, drag_area_normal=1.0, drag_area_tangential=1.0,
                axis_angle_deg=999.0)
    times = tuple(np.linspace(0.0, 60.0, 305))
    top = TopMotion(y=(Sinusoid(amplitude=1.0, frequency=2 * math.pi / 6.0),),
                    series=TimeSeries(times=times, x=(0.0,) * 305, y=(0.0,) * 305),
                    ramp_s=0.0)   # abrupt: slack within the first 9 s
    scene = single_section_scene(cable=cable, body=body, environment=Environment(density=1025.0),
                                 top_motion=top, numerics=Numerics(duration=DURATION, output_step=0.1,
                                                                   integrator=METHOD, rtol=1e-6, atol=1e-8))
    r = simulate(scene)
    print(json.dumps({"success": r.success, "events": len(r.events), "t_end": float(r.time[-1])}))
""")


@pytest.mark.parametrize("method", ["cvodes", "idas"])
def test_series_with_slack_does_not_abort(method):
    code = SCRIPT.replace("DURATION", "9.0").replace("METHOD", repr(method))
    proc = subprocess.run([sys.executable, "-c", code], check=False, capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, f"exit {proc.returncode}:\n{proc.stderr[-3000:]}"
    out = json.loads(proc.stdout.strip().splitlines()[-1])
    assert out["success"] and out["t_end"] == pytest.approx(9.0)
    assert out["events"] >= 2          # the cable did go slack and taut again: the locator ran
