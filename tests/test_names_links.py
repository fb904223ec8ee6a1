"""Names that mean one thing and commands that link: the segmented cable's stretch u (the element
elongations) against its chord, the steady tow's shape lines, and the design's active constraints."""

import dataclasses

import numpy as np
import pytest

from cablesys.model.segmented import build_segmented_model
from cablesys.result_protocol import long_name_of, unit_of
from cablesys.scene import dale_scene
from cablesys.statics import steady_state


def _sagging(n=6):
    """Dale's scene, 6 elements, in a 1.5 m/s current: the cable bows, so its chord is shorter than it."""
    sc = dale_scene(duration=1.0).replace_section(0, cable={"segments": n})
    env = dataclasses.replace(sc.environment, current_depths=(0.0,), current_speeds=(1.5,))
    return sc.replace(environment=env)


def test_segmented_u_is_the_element_stretch_and_the_chord_is_named_apart():
    sc = _sagging()
    model = build_segmented_model(sc)
    p = model.parameters(sc)
    st = steady_state(model, p)
    y = st.outputs
    x = np.asarray([y[f"node_x[{k}]"] for k in range(7)])
    yy = np.asarray([y[f"node_y[{k}]"] for k in range(7)])
    l_0 = sc.cable.length_zero
    # independent route: the polyline through the nodes
    along = float(np.sum(np.hypot(np.diff(x), np.diff(yy)))) - l_0
    chord = float(np.hypot(x[-1] - x[0], yy[-1] - yy[0])) - l_0
    assert y["u"] == pytest.approx(along, rel=1e-9, abs=1e-12)
    assert y["chord_stretch"] == pytest.approx(chord, rel=1e-9, abs=1e-12)
    # the cable bows: the chord is shorter than the stretched cable by more than the solver's tolerance
    assert y["chord_stretch"] < y["u"] - 1e-6
    # the stretch is elastic: the sum over elements of T_k h_r / AE (taut elements, no damping at rest)
    tension = np.asarray([y[f"element_tension[{k}]"] for k in range(6)])
    assert y["u"] == pytest.approx(float(np.sum(tension / sc.cable.ae)) * sc.cable.length / 6, rel=1e-6)
    assert unit_of("chord_stretch") == "m" and "chord" in long_name_of("chord_stretch")
    assert "zero-tension" in long_name_of("u")
