"""One name per physical quantity across the three models; old slack keys still load, with a warning.

The shared quantities are the table ``QUANTITIES`` of :mod:`cablesys.scene.fields` (name ->
dimension, symbol). The Wang scene, the slack model and the towed model must use those names,
units and symbols for them; a field with a shared quantity's symbol but another name, or with a
shared name but another dimension, fails here.
"""

import dataclasses
import math
import tomllib

import pytest

from cablesys.errors import ParameterError
from cablesys.model.fluid import quadratic_drag
from cablesys.scene import Cable as WangCable
from cablesys.scene import Environment
from cablesys.scene.fields import QUANTITIES, SI_UNIT
from cablesys.slack import SlackCable
from cablesys.slack import PointMass, SlackScene
from cablesys.slack.scene import EXAMPLE_TOML, scene_from_dict
from cablesys.towed import REPORT_SEA_TRIAL, TowedCable, TowedScene, TowedSceneCable, amplification, theory_coefficients

# the input classes of the three models
WANG = (WangCable, Environment)
SLACK = (SlackCable, PointMass, SlackScene)
TOWED = (TowedCable, TowedSceneCable, TowedScene)
MODELS = {"wang": WANG, "slack": SLACK, "towed": TOWED}
# names of the dialects issue 10 removed: none may come back as a field of any model
DIALECT = {"axial_stiffness", "added_mass_coefficient", "submerged_weight_per_length", "EA", "c_d", "cd", "ca",
           "c_a", "c_am", "cn", "ct", "weight_in_water", "mass_per_unit_length", "dia"}


def _fields(classes):
    return [(cls, f) for cls in classes for f in dataclasses.fields(cls)]


ALL = _fields(WANG + SLACK + TOWED)


def _names(classes):
    return {f.name for _, f in _fields(classes)}


@pytest.mark.parametrize("cls,f", _fields(SLACK + TOWED), ids=lambda x: getattr(x, "name", getattr(x, "__name__", "")))
def test_every_slack_and_towed_field_carries_unit_and_symbol(cls, f):
    meta = f.metadata
    assert meta.get("dim") in SI_UNIT, f"{cls.__name__}.{f.name} has no dimension"
    assert meta.get("unit") == SI_UNIT[meta["dim"]], f"{cls.__name__}.{f.name}: unit {meta.get('unit')!r}"
    assert "symbol" in meta and meta.get("doc"), f"{cls.__name__}.{f.name} has no symbol or meaning"


def test_wang_fields_carry_their_unit():
    for cls, f in _fields(WANG):
        assert f.metadata.get("unit") == SI_UNIT[f.metadata["dim"]], f"{cls.__name__}.{f.name}"
    # the Wang cable declares every shared quantity it has from the one table
    assert {f.name for f in dataclasses.fields(WangCable) if "quantity" in f.metadata} == {
        "length", "ae", "diameter", "mass_per_length", "weight_per_length", "added_mass_factor", "cd_normal",
        "ct_tangential"}


@pytest.mark.parametrize("cls,f", ALL, ids=[f"{c.__name__}.{f.name}" for c, f in ALL])
def test_a_shared_quantity_has_one_name_unit_and_symbol(cls, f):
    meta = f.metadata
    if "quantity" in meta:                       # declared with fields.quantity(name, ...)
        assert f.name == meta["quantity"], f"{cls.__name__}.{f.name} stands for {meta['quantity']!r}: use that name"
    if f.name in QUANTITIES:
        assert meta.get("quantity") == f.name, f"{cls.__name__}.{f.name}: declare it with fields.quantity({f.name!r}, ...)"
        dim, symbol = QUANTITIES[f.name]
        assert meta.get("dim") == dim, f"{cls.__name__}.{f.name}: dimension {meta.get('dim')} is not {dim}"
        if "symbol" in meta:
            assert meta["symbol"] == symbol, f"{cls.__name__}.{f.name}: symbol {meta['symbol']} is not {symbol}"
    for name, (dim, symbol) in QUANTITIES.items():
        if meta.get("symbol") == symbol and meta.get("dim") == dim:
            assert f.name == name, f"{cls.__name__}.{f.name} is the quantity {symbol} [{SI_UNIT[dim]}]: name it {name}"
    assert f.name not in DIALECT, f"{cls.__name__}.{f.name} is an old dialect name"


def test_one_name_means_one_dimension_across_models():
    dims = {}
    for cls, f in ALL:
        dims.setdefault(f.name, set()).add((f.metadata.get("dim"), cls.__name__))
    clash = {n: d for n, d in dims.items() if len({dim for dim, _ in d}) > 1}
    assert not clash, f"one name, several dimensions: {clash}"


def test_the_quantities_the_models_share_have_the_same_names():
    wang, slack, towed = (_names(c) for c in MODELS.values())
    # mass per length, weight in water per length, axial stiffness, added-mass factor (Wang and slack)
    assert {"length", "mass_per_length", "weight_per_length", "ae", "added_mass_factor"} <= wang & slack
    assert {"gravity"} <= wang & slack
    # the towed cable's dimensions, mass, drag coefficients and fluid (Wang and towed scene)
    assert {"length", "diameter", "mass_per_length", "ct_tangential", "cd_normal", "density"} <= wang & towed


def test_towed_tangential_coefficient_in_wang_convention_gives_the_same_friction():
    """K&S (1981) eq. 1b, F_t = rho/2 pi d_c c_t U^2, equals Wang (1971) eq. 44 with C_t = pi c_t.

    The towed model keeps the report's c_t (referred to pi d_c); ``ct_tangential`` is the same
    friction in the Wang scene's name and convention, checked through the Wang model's drag law.
    """
    cab = TowedCable(length=500.0, speed=4.0, **REPORT_SEA_TRIAL)
    rho, U = 1025.0, cab.speed
    f_ks = 0.5 * rho * math.pi * cab.diameter * cab.c_t * U**2
    f_wang = float(quadratic_drag(rho, cab.ct_tangential * cab.diameter, U))
    assert f_wang == pytest.approx(f_ks, rel=1e-14)
    # and the report's tension at the tow point, T(0) = M U^2 D (eq. 20a), is that friction over L plus the drogue
    M = rho * math.pi * cab.diameter**2 / 4
    assert M * U**2 * cab.drag_term == pytest.approx(f_ks * cab.length + 2 * cab.c_t_drogue * M * U**2, rel=1e-12)


def test_old_slack_keys_are_deprecated_aliases():
    doc = tomllib.loads(EXAMPLE_TOML.replace("ae = ", "axial_stiffness = "))
    doc["masses"][0]["added_mass_coefficient"] = 0.8
    with pytest.warns(DeprecationWarning) as caught:
        scene = scene_from_dict(doc)
    assert sorted(str(w.message) for w in caught) == [
        "cable.axial_stiffness is deprecated: write ae",
        "masses[0].added_mass_coefficient is deprecated: write added_mass_factor"]
    new = scene_from_dict(tomllib.loads(EXAMPLE_TOML))
    assert scene.cable.ae == new.cable.ae and scene.masses[0].added_mass_factor == 0.8
    doc["cable"]["ae"] = 1.0
    with pytest.raises(ParameterError, match="old name of cable.ae"):
        scene_from_dict(doc)


def test_old_submerged_weight_key_loads_as_weight_per_length():
    """A file of the old vocabulary gives the same scene as the new one, with a warning naming the key."""
    def doc_with(key):
        doc = tomllib.loads(EXAMPLE_TOML)
        doc["scene"]["medium"] = "water"
        doc["cable"].update({"specific_gravity": 7.8, key: 9.0})
        for m in doc["masses"]:
            m["specific_gravity"] = 2.0
        return doc
    with pytest.warns(DeprecationWarning, match="cable.submerged_weight_per_length is deprecated: write weight_per_length"):
        old = scene_from_dict(doc_with("submerged_weight_per_length"))
    new = scene_from_dict(doc_with("weight_per_length"))
    assert old == new and new.cable.weight_per_length == 9.0
    # the value is used: weight in water per length is 9 N/m, not m g (1 - 1/S)
    assert new.cable.weight_and_added_mass("water", new.gravity)[0] == 9.0


def test_slack_and_towed_names_do_not_clash_with_the_top_level_and_share_the_verbs():
    """``from cablesys import *`` and ``from cablesys.slack import *`` together: no class or loader
    shadows another model's; the verbs are the same words (``modes``, ``analyze``)."""
    import cablesys
    import cablesys.slack
    import cablesys.towed

    top = set(cablesys.__all__)
    for pkg in (cablesys.slack, cablesys.towed):
        nouns = {n for n in pkg.__all__ if n[0].isupper() or n.startswith("load_")}
        assert not nouns & top, f"{pkg.__name__} exports {sorted(nouns & top)}, names of the Wang model"
        assert {"modes", "analyze"} <= set(pkg.__all__)
    assert "modes" in top
    # the old names are still readable, with a warning that names the new one
    with pytest.warns(DeprecationWarning, match="use cablesys.slack.SlackCable"):
        assert cablesys.slack.Cable is SlackCable
    with pytest.warns(DeprecationWarning, match="load_slack_scene"):
        assert cablesys.slack.load_scene is cablesys.slack.load_slack_scene


SCENE_CABLE = dict(diameter=0.016, mass_per_length=0.25, ct_tangential=0.03, cd_normal=1.2)


@pytest.mark.parametrize("U", [1.5, 5.0])
def test_towed_theory_coefficients_give_the_wang_drag_forces(U):
    """The one conversion of C_t, C_n and the drogue (equation.theory_coefficients), through Wang's drag law.

    Kennedy & Strahan (1981): F_t = rho/2 pi d c_t U^2 (eq. 1b); tension at the drogue end
    T(L) = 2 c_t' M U^2 with M = rho pi d^2 / 4 (eq. 1-3); the drogue replaced by a cable
    lengthened by d c_t' / c_t (p. 10); c_n* = A c_n (eq. 39) with A = 1 for a level cable (eq. 38).
    """
    rho, CDA = 1025.0, 0.3
    th = theory_coefficients(**SCENE_CABLE, density=rho, drogue_drag_area=CDA)
    d = SCENE_CABLE["diameter"]
    M = rho * math.pi * d**2 / 4
    friction = float(quadratic_drag(rho, SCENE_CABLE["ct_tangential"] * d, U))      # Wang eq. 44, per length
    assert 0.5 * rho * math.pi * d * th["c_t"] * U**2 == pytest.approx(friction, rel=1e-14)
    drogue = float(quadratic_drag(rho, CDA, U))                                        # the drogue's drag, N
    assert 2 * th["c_t_drogue"] * M * U**2 == pytest.approx(drogue, rel=1e-14)
    assert friction * d * th["c_t_drogue"] / th["c_t"] == pytest.approx(drogue, rel=1e-13)
    assert th["beta"] == pytest.approx(M / (M + SCENE_CABLE["mass_per_length"]), rel=1e-15)
    # level cable: A(theta, 0) = 1 at any angle, so c_n is Wang's C_n; a depressed cable scales it
    for theta in (0.05, 0.4, 1.2):
        assert float(amplification(theta, 0.0)) == pytest.approx(1.0, rel=1e-12)
    A = float(amplification(0.1, 0.3))
    assert theory_coefficients(**SCENE_CABLE, amplification=A)["c_n"] == pytest.approx(A * 1.2, rel=1e-15)
    assert th["c_n"] == SCENE_CABLE["cd_normal"]


def test_towed_scene_reaches_the_theory_through_the_conversion():
    """TowedScene -> TowedCable carries exactly theory_coefficients' numbers (no second conversion)."""
    cab = TowedSceneCable(length=800.0, **SCENE_CABLE)
    scene = TowedScene(cable=cab, speed=3.0, drogue_drag_area=0.2, amplification=2.0, density=1000.0)
    tc = scene.towed_cable()
    ref = theory_coefficients(**SCENE_CABLE, density=1000.0, drogue_drag_area=0.2, amplification=2.0)
    assert {k: getattr(tc, k) for k in ref} == ref
    assert (tc.length, tc.speed, tc.diameter) == (800.0, 3.0, 0.016)
    # and back: the theory cable's Wang-convention C_t is the scene's
    assert tc.ct_tangential == pytest.approx(cab.ct_tangential, rel=1e-15)
    with pytest.raises(ParameterError, match="cable.cd_normal"):
        TowedSceneCable(length=800.0, **{**SCENE_CABLE, "cd_normal": 0.0})
