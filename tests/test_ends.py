"""The anchored line on a seabed: scene fields and their errors, the closed-form catenary with seabed
friction, the node model's statics against it (second order in N, 1e-6 after Richardson), a line on
a sloped bed and a resting line (studies/ends_checks.py; the energy of a bouncing line is checked on the study's own
run, tests/test_ends_study.py)."""

import math
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "studies"))
import ends_checks as E  # noqa: E402

from cablesys.errors import ParameterError  # noqa: E402
from cablesys.model import build_model  # noqa: E402
from cablesys.model.params import parameter_items, structure_of  # noqa: E402
from cablesys.scene import Anchor, Body, Cable, Seabed, dump_scene, scene_from_dict, single_section_scene  # noqa: E402
from cablesys.statics.closed_forms import seabed_catenary, seabed_catenary_span  # noqa: E402

pytestmark = pytest.mark.filterwarnings("ignore")
BODY = Body(weight=0.0, mass_x=1.0, mass_y=1.0)


def test_scene_without_ends_keeps_todays_structure_and_functions():
    plain = single_section_scene(cable=E.chain(8), body=BODY)
    ends = single_section_scene(cable=E.chain(8), body=BODY, anchor=Anchor(x=250.0, y=100.0), seabed=Seabed(depth=100.0))
    assert structure_of(ends)[:-1] == structure_of(plain) and len(structure_of(plain)) == 10
    labels = [lb for lb, _ in parameter_items(plain)]
    assert not [lb for lb in labels if lb.startswith(("anchor.", "seabed."))]
    m0, m1 = build_model(plain), build_model(ends)
    assert m0.static_force is None and m0.nq == 16 and m1.nq == 14      # the anchor's node is no coordinate
    assert "seabed_normal[0]" not in m0.output_labels and "seabed_normal[8]" in m1.output_labels


def test_toml_round_trip_and_fps_units():
    sc = single_section_scene(cable=E.chain(8), body=BODY, anchor=Anchor(x=250.0, y=100.0),
                              seabed=Seabed(depth=100.0, slope_deg=2.0, stiffness=4e6, damping=1e5, friction_axial=0.3,
                                            friction_lateral=0.6))
    import tomllib
    for units in ("SI", "fps"):
        back = scene_from_dict(tomllib.loads(dump_scene(sc, units=units)))
        assert back.anchor.x == pytest.approx(250.0, rel=1e-12) and back.seabed.stiffness == pytest.approx(4e6, rel=1e-12)
        assert back.seabed.friction_lateral == 0.6 and back.seabed.slope_deg == 2.0
    assert "stiffness = 4000000.0" in dump_scene(sc) and "stiffness = 4000000.0" not in dump_scene(sc, units="fps")


@pytest.mark.parametrize("make, field", [
    (lambda: dict(anchor=Anchor(x=400.0, y=100.0)), "cable.length"),                        # 300 m < 412 m chord
    (lambda: dict(anchor=Anchor(x=250.0, y=100.0), seabed=Seabed(depth=90.0)), "seabed.depth"),  # anchor under the bed
    (lambda: dict(seabed=Seabed(depth=100.0, friction_axial=-0.1)), "seabed.friction_axial"),
    (lambda: dict(seabed=Seabed(depth=100.0, friction_lateral=-1.0)), "seabed.friction_lateral"),
    (lambda: dict(anchor=Anchor(x=250.0, y=math.nan)), "anchor.y"),
    (lambda: dict(seabed=Seabed(depth=100.0, slope_deg=70.0)), "seabed.slope_deg"),
])
def test_bad_ends_are_named_errors_before_any_work(make, field):
    """Each raised while the scene is made (no model is built), naming the field and its value."""
    with pytest.raises(ParameterError) as err:
        single_section_scene(cable=E.chain(8), body=BODY, **make())
    assert err.value.field == field and str(err.value).startswith(field)


def test_a_chain_of_sections_shorter_than_its_anchor_chord_is_named():
    """Chain-wire-chain: the line's length is every section's (3 x 130 m = 390 m < the 412 m to the anchor at (400, 100)),
    named at the last section's cable.length; 3 x 140 m reaches."""
    from cablesys.scene import Scene, Section
    line = lambda length: tuple(Section(cable=E.chain(4, length), body=BODY) for _ in range(3))
    with pytest.raises(ParameterError) as err:
        Scene(sections=line(130.0), anchor=Anchor(x=400.0, y=100.0))
    assert err.value.field == "sections[2].cable.length" and "390 m long" in str(err.value)
    assert "412.311 m" in str(err.value)
    Scene(sections=line(140.0), anchor=Anchor(x=400.0, y=100.0))


def test_ends_need_the_node_model():
    with pytest.raises(ParameterError, match="cable.segments"):
        single_section_scene(cable=E.chain(1), body=BODY, anchor=Anchor(x=250.0, y=100.0))


def test_closed_form_reaches_its_fairlead_and_lays_its_bed_length():
    """The shape ends at (X, Z); L_B = L - V_F / w; friction lowers the anchor force by mu w L_B (mu = 0.1)
    or to zero (mu = 5), the span inverse gives back L_B; the hanging line has V_A = V_F - w L > 0."""
    L, w, ea, Z = E.LENGTH, E.W, E.EA, E.DEPTH
    for mu in E.FRICTIONS:
        X = seabed_catenary_span(length=L, weight_per_length=w, ea=ea, height=Z, seabed_length=120.0, friction=mu)
        c = seabed_catenary(length=L, weight_per_length=w, ea=ea, span=X, height=Z, friction=mu)
        x, z, T = c["shape"](np.array([0.0, c["L_B"], L]))
        assert c["L_B"] == pytest.approx(120.0, rel=1e-10) and c["V_F"] == pytest.approx(w * (L - 120.0), rel=1e-12)
        assert (x[-1], z[-1]) == pytest.approx((X, Z), rel=1e-12) and z[1] == 0.0
        assert c["H_A"] == pytest.approx(max(c["H"] - mu * w * 120.0, 0.0), rel=1e-12, abs=1e-9)
        assert T[0] == pytest.approx(c["H_A"], abs=1e-9) and T[-1] == pytest.approx(math.hypot(c["H"], c["V_F"]))
    c = seabed_catenary(length=L, weight_per_length=w, ea=ea, span=282.0, height=Z)
    assert c["L_B"] == 0.0 and c["V_A"] == pytest.approx(c["V_F"] - w * L) and c["V_A"] > 0


@pytest.fixture(scope="module")
def convergence():
    return E.catenary_convergence((40, 80, 160))


def test_statics_equal_the_closed_form_at_second_order(convergence):
    """Fairlead H and V_F, anchor H_A (V_A when hanging), length on the bed, for mu = 0, 0.1, 5 and a
    hanging line: observed orders 2 +- 0.05 between N = 80 and 160, Richardson to 1e-6."""
    assert set(convergence["cases"]) == {"mu=0", "mu=0.1", "mu=5", "no touch"}
    for name, case in convergence["cases"].items():
        for key, order in case["order"].items():
            assert abs(order - 2.0) < 0.05, (name, key, order)
        for key, errs in case["errors"].items():
            if key == "H_A" and name == "mu=5":        # slack at the anchor: H_A = 0 at every N
                assert max(abs(v) for v in errs) < 1e-6
    assert convergence["max_rel_err"] < 1e-6
    # the friction is felt: the closed form's anchor force differs by mu w L_B, and the statics follow it
    _, c0 = E.catenary_case(0.0)
    _, c1 = E.catenary_case(0.1)
    assert c0["H_A"] - c1["H_A"] > 0.2 * c0["H_A"]
    assert abs(convergence["cases"]["mu=0.1"]["errors"]["H_A"][-1]) < 2e-4


def test_line_on_a_sloped_seabed():
    """Tension grows up a frictionless 10 degree slope by w sin(alpha) per metre: fairlead and anchor to 1e-9."""
    err = E.sloped_case(20)
    assert max(abs(v) for v in err.values()) < 1e-9


def test_resting_line_does_not_creep():
    """From its static state (mu = 0, MoorDyn's default bed stiffness and damping) for 1000 s."""
    assert E.resting(1000.0, 0.0) < 1e-6


@pytest.mark.parametrize("sway", [False, True])
def test_a_line_hanging_free_between_the_top_and_an_anchor_is_the_catenary(sway):
    """No seabed: the node statics start from the default guess (a span pulled taut between its ends) and reach
    the catenary through both supports; a nearly inextensible line's top tension is w a cosh((0 - X0) / a) with a
    from sqrt(L^2 - v^2) = 2 a sinh(h / 2a) (Irvine 1981 ch. 1), at the lumped weights' second order."""
    from scipy.optimize import brentq
    from cablesys.statics.catenary import segmented_steady
    L, h, v, w = 120.0, 80.0, 60.0, 18.0
    text = f"""
[cable]
length = {L}
ae = 4.0e7
diameter = 0.024
mass_per_length = 2.4
weight_per_length = {w}
segments = 40
[body]
weight = 100.0
mass_x = 20.0
mass_y = 20.0
[anchor]
x = {h}
y = {v}
""" + ("[numerics]\ndimensions = 3\n" if sway else "")
    import tomllib
    sc = scene_from_dict(tomllib.loads(text))
    model = build_model(sc)
    st = segmented_steady(model, model.parameters(sc))
    u = brentq(lambda u: np.sinh(u) / u - math.sqrt(L**2 - v**2) / h, 1e-9, 20.0)
    a = h / (2 * u)
    x0 = 0.5 * h - a * math.atanh(-v / L)
    assert st.outputs["tension_top"] == pytest.approx(w * a * math.cosh(x0 / a), rel=2e-3)
    low = max(st.q.reshape(-1, 3 if sway else 2)[:, 1])                      # the sag below the top (y down)
    assert low == pytest.approx(a * (math.cosh(x0 / a) - 1.0), rel=2e-3)


@pytest.mark.parametrize("stiffness", [1e7, 1e8])
def test_a_stiff_nearly_taut_span_reaches_its_catenary(stiffness):
    """A stiff line (AE / w L = 1e7, 1e8) nearly taut between the top and its anchor (chord 99.81 m of 100 m): the
    statics start from the lumped line shot to the anchor (KINSOL had stalled from the geometric guess at N = 10,
    residual 1.5e-3) and converge to the inextensible catenary's top tension w a cosh(X0 / a) (Irvine 1981 ch. 1)
    at second order in N."""
    from scipy.optimize import brentq
    from cablesys.statics.catenary import segmented_steady
    w, L, h, v = 10.0, 100.0, 30.0, 95.2
    u = brentq(lambda u: np.sinh(u) / u - math.sqrt(L**2 - v**2) / h, 1e-9, 50.0)
    a = h / (2 * u)
    top = w * a * math.cosh((0.5 * h - a * math.atanh(-v / L)) / a)
    errors = []
    for n in (10, 20):
        cable = Cable(length=L, ae=stiffness * w * L, diameter=0.02, mass_per_length=1.2, weight_per_length=w,
                      segments=n)
        sc = single_section_scene(cable=cable, body=BODY, anchor=Anchor(x=h, y=v))
        model = build_model(sc)
        errors.append(segmented_steady(model, model.parameters(sc)).outputs["tension_top"] / top - 1.0)
    assert abs(errors[1]) < 2e-3
    assert math.log2(errors[0] / errors[1]) == pytest.approx(2.0, abs=0.15)


def test_a_moored_run_names_the_anchor_end_as_the_anchor(tmp_path, capsys):
    """The last section's lower end is the anchor: the run's console line and figure call its tension the anchor's,
    not the body's (the 'body' of that section only loads the anchor)."""
    from cablesys.cli import main
    scene = E.mooring_scene(8, 250.0, duration=4.0, output_step=0.5)
    f = tmp_path / "moor.toml"
    f.write_text(dump_scene(scene))
    assert main(["run", str(f), "--out", str(tmp_path / "out")]) == 0
    printed = capsys.readouterr().out
    assert "tension at the anchor min/max" in printed and "tension at the body" not in printed
    import json
    assert json.loads((tmp_path / "out" / "summary.json").read_text())["tension_bottom_at"] == "at the anchor"
