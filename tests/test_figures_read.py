"""The figures read at a glance: on synthetic results with known answers, the data of interest lies
within the axes, every drawn mark is in a legend, a steady series has no offset notation, limits do
not set the tension axis, the mode figure stays bounded with many modes and is drawn about the real
rest shape, and RAO axes frame the forcing and the modes it excites.

No simulation runs here: each figure is fed a result built from closed forms, so a failure is the
plot's own."""

from types import SimpleNamespace

import numpy as np
import pytest

import cablesys.linear.plots as linear_plots
import cablesys.plots.time_domain as td_plots
from cablesys.linear.frequency_response import RAO
from cablesys.linear.modal import Modes
from cablesys.plots.axes import is_steady
from cablesys.time_result import SnapLoad, TimeResult
from cablesys.units import LBF


@pytest.fixture
def figures(monkeypatch):
    """The figures the plot functions save (drawn and closed), in order."""
    seen = []
    for mod in (td_plots, linear_plots):
        original = mod.save_figure

        def grab(fig, path, _orig=original, **kw):
            out = _orig(fig, path, **kw)       # lays out and draws: extents and offsets are final
            seen.append(fig)
            return out
        monkeypatch.setattr(mod, "save_figure", grab)
    return seen


def _axis(fig, title_part):
    found = [a for a in fig.axes if title_part in a.get_title()]
    assert len(found) == 1, f"{len(found)} axes titled '*{title_part}*': {[a.get_title() for a in fig.axes]}"
    return found[0]


def _marks(ax):
    """Data artists drawn on ``ax``: lines, filled spans and marker collections (not grid lines)."""
    return [a for a in list(ax.lines) + list(ax.patches) + list(ax.collections)]


def _style(art):
    from matplotlib.colors import to_rgba
    return (to_rgba(art.get_color()), art.get_linestyle(), art.get_marker())


def _assert_legend_complete(ax):
    """Every mark drawn on ``ax`` is in its legend: by its label, or (a line repeated under one entry,
    like numbered natural frequencies) by the style of a labelled line that is."""
    legend = ax.get_legend()
    shown = {t.get_text() for t in legend.get_texts()} if legend is not None else set()
    labelled = {_style(ln) for ln in ax.lines if ln.get_label() in shown}
    for art in _marks(ax):
        label = art.get_label()
        if label.startswith("_") and hasattr(art, "get_linestyle") and hasattr(art, "get_marker"):
            assert _style(art) in labelled, f"an unlabelled line of a style not in the legend on '{ax.get_title()}'"
            continue
        assert label and not label.startswith("_"), f"an unlabelled mark ({type(art).__name__}) on '{ax.get_title()}'"
        assert label in shown, f"'{label}' drawn on '{ax.get_title()}' but not in its legend {sorted(shown)}"


def _assert_no_offset(fig):
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            offset = axis.get_major_formatter().get_offset() if hasattr(axis.get_major_formatter(), "get_offset") else ""
            assert offset == "", f"offset notation '{offset}' on '{ax.get_title()}'"


def _run(t, *, tension_top, tension_bottom, phi, u, x_b, y_b, x_s=None, y_s=None, nodes=None, **kw):
    data = {"phi": phi, "u": u, "x_b": x_b, "y_b": y_b, "tension_mid": 0.5 * (tension_top + tension_bottom),
            "tension_top": tension_top, "tension_bottom": tension_bottom,
            "x_s": np.zeros_like(t) if x_s is None else x_s, "y_s": np.zeros_like(t) if y_s is None else y_s}
    for k, (x, y) in enumerate(nodes or ()):
        data[f"node_x[{k}]"], data[f"node_y[{k}]"] = x, y
    return TimeResult(time=t, data=data, scene_name="synthetic", **kw)


def _snapping_lift():
    """A lift whose top tension swings 2-25 kN with a snap of 31 kN at t = 40 s (peak known)."""
    t = np.linspace(0.0, 60.0, 1201)
    wave = np.sin(2 * np.pi * t / 6.0)
    top = 13.5e3 + 11.5e3 * wave
    top[t == 40.0] = 31e3
    return _run(t, tension_top=top, tension_bottom=top - 1.5e3, phi=0.02 * wave, u=0.05 + 0.02 * wave,
                x_b=0.3 * wave, y_b=300.0 + 0.8 * wave, y_s=np.sin(2 * np.pi * t / 6.0),
                snaps=(SnapLoad(time=40.0, section=1, tension=31e3),))


def test_limits_annotate_the_tension_panel_without_setting_its_scale(tmp_path, figures):
    run = _snapping_lift()
    limits = SimpleNamespace(working_load=126e3, least_tension=1e3, slack_fraction=0.1)
    td_plots.plot_time_series(run, tmp_path / "ts.png", limits=limits, window_start=12.0)
    ax = _axis(figures[0], "tension")
    lo, hi = ax.get_ylim()
    assert lo <= 0.5 and hi >= 31.0, f"the traces and the 31 kN snap leave the axis [{lo}, {hi}] kN"
    assert hi < 1.2 * 31.0, f"the tension axis reaches {hi} kN: the 126 kN working load set its scale"
    notes = [t.get_text() for t in ax.texts]
    assert any("working load 126000" in n or "working load 126 kN" in n for n in notes) and \
        any("above" in n for n in notes), notes
    assert any(ln.get_label().startswith("least allowed tension 1 kN") for ln in ax.lines)   # inside: a line
    # the verdict's slack check: 10 % of the trace's mean over the statistics window (t >= 12 s)
    slack = [ln for ln in ax.lines if ln.get_label().startswith("slack limit (top")]
    top = run["tension_top"][run.time >= 12.0]
    assert len(slack) == 1 and slack[0].get_ydata()[0] == pytest.approx(0.1 * top.mean() / 1e3)
    _assert_legend_complete(ax)
    for title in ("swing angle", "cable stretch"):         # the statistics-window band is in their legends too
        _assert_legend_complete(_axis(figures[0], title))


def test_working_load_inside_the_data_is_a_line():
    """The other branch: a limit within the traces' range is drawn (and labelled) where it is."""
    import matplotlib.pyplot as plt
    from cablesys.plots.axes import limit_lines
    fig, ax = plt.subplots()
    ax.plot([0, 1], [2.0, 25.0], label="trace")
    limit_lines(ax, {"working load": 20.0}, 2.0, 25.0, "kN")
    assert [ln.get_ydata()[0] for ln in ax.lines if ln.get_label().startswith("working load")] == [20.0]
    assert not ax.texts
    plt.close(fig)


def test_a_steady_tow_states_its_values_and_draws_its_shape(tmp_path, figures):
    """A steady tow at 56 deg: angle 56 deg + 1e-11 deg noise, 12 elements on a straight 300 m line.
    The figure shows no offset notation, states the angle, and draws the shape with its closed-form
    depth 300 cos 56 deg and layback -300 sin 56 deg."""
    t = np.linspace(0.0, 20.0, 401)
    rng = np.random.default_rng(1)
    noise = 1e-13 * rng.standard_normal(t.size)
    a = np.radians(56.0)
    s = np.linspace(0.0, 300.0, 13)
    nodes = [(-sk * np.sin(a) + noise, sk * np.cos(a) + noise) for sk in s]
    run = _run(t, tension_top=6388.2 + 1e-9 * noise, tension_bottom=np.full_like(t, 2186.7), phi=a + noise,
               u=np.full_like(t, -0.97), x_b=nodes[-1][0], y_b=nodes[-1][1], nodes=nodes)
    td_plots.plot_time_series(run, tmp_path / "tow.png", limits=SimpleNamespace(working_load=126e3, least_tension=None))
    fig = figures[0]
    _assert_no_offset(fig)
    phi_ax = _axis(fig, "swing angle")
    assert [ln.get_label() for ln in phi_ax.lines] == ["lower body: steady 56 deg"]
    lo, hi = phi_ax.get_ylim()
    assert lo < 56.0 < hi and hi - lo < 0.2 * 56.0
    shape = _axis(fig, "cable shape")
    title = shape.get_title()
    assert f"depth {300 * np.cos(a):.4g} m" in title and f"layback {-300 * np.sin(a):+.4g} m" in title, title
    rest = [ln for ln in shape.lines if ln.get_label().startswith("shape")][0]
    np.testing.assert_allclose(rest.get_xdata(), -s * np.sin(a), atol=1e-9)
    x0, x1 = sorted(shape.get_xlim())
    y0, y1 = sorted(shape.get_ylim())
    assert x0 <= -300 * np.sin(a) and x1 >= 0 and y0 <= 0 and y1 >= 300 * np.cos(a)
    _assert_legend_complete(shape)
    _assert_legend_complete(_axis(fig, "tension"))


def test_fps_labels_carry_fps_units(tmp_path, figures):
    td_plots.plot_time_series(_snapping_lift(), tmp_path / "fps.png", units="fps")
    fig = figures[0]
    labels = [a.get_ylabel() for a in fig.axes] + [a.get_xlabel() for a in fig.axes]
    assert all(("(" in lb and ")" in lb) for lb in labels), labels
    joined = " ".join(labels)
    assert "(ft" in joined and ("(lbf)" in joined or "(kip)" in joined) and "(m" not in joined and "(N)" not in joined
    ax = _axis(fig, "tension")
    assert ax.get_ylim()[1] >= 31e3 / LBF * (1e-3 if "kip" in ax.get_ylabel() else 1.0)


def test_is_steady_separates_noise_from_motion():
    assert is_steady(58.96 + 1e-11 * np.sin(np.arange(100)), atol=1e-9)
    assert not is_steady(58.96 + 1e-3 * np.sin(np.arange(100)), atol=1e-9)
    assert is_steady(1e-19 * np.arange(5), atol=1e-9)          # rounding residue about zero


def _segmented_modes(n_el=12, length=300.0, offset=21.0):
    """A 12-element cable whose rest shape leans to x = 21 m at the body; 24 modes, node coordinates
    as generalized coordinates (Cq = identity on the node rows, as in the segmented model)."""
    s = np.linspace(0.0, 1.0, n_el + 1)
    x0, y0 = offset * s, length * s
    labels = tuple(f"{c}[{j}]" for j in range(1, n_el + 1) for c in ("x", "y"))
    out = [f"node_x[{k}]" for k in range(n_el + 1)] + [f"node_y[{k}]" for k in range(n_el + 1)]
    Cq = np.zeros((len(out), len(labels)))
    for j in range(1, n_el + 1):
        Cq[j, 2 * (j - 1)] = 1.0
        Cq[n_el + 1 + j, 2 * (j - 1) + 1] = 1.0
    rest = SimpleNamespace(output_labels=tuple(out), y0=np.concatenate([x0, y0]), Cq=Cq)
    nq = len(labels)
    shapes = np.eye(nq)
    w = np.geomspace(0.07, 300.0, nq)
    modes = Modes(q_labels=labels, omega_undamped=w, shapes=shapes, omega_damped=w, omega_natural=w,
                  damping_ratio=np.full(nq, 0.02), eigenvalues=-0.02 * w + 1j * w)
    return modes, rest, x0, y0


def test_many_modes_stay_bounded_and_are_drawn_about_the_rest_shape(tmp_path, figures):
    modes, rest, x0, y0 = _segmented_modes()
    path = linear_plots.plot_modes(modes, rest, tmp_path / "modes.png")
    fig = figures[0]
    w, h = fig.get_size_inches() * 110
    assert w <= 1600 and h <= 1400, f"{w:.0f} x {h:.0f} px for 24 modes"
    from PIL import Image
    assert max(Image.open(path).size) <= 1600
    panels = [a for a in fig.axes if a.get_title().startswith("mode ")]
    assert len(panels) == linear_plots.MAX_MODE_PANELS
    for ax in panels:
        rest_line = [ln for ln in ax.lines if ln.get_label() == "at rest"][0]
        np.testing.assert_allclose(rest_line.get_xdata(), x0)       # the 21 m offset, not a vertical line
        np.testing.assert_allclose(rest_line.get_ydata(), y0)
        xa, xb = sorted(ax.get_xlim())
        ya, yb = sorted(ax.get_ylim())
        for ln in ax.lines:
            assert xa <= np.min(ln.get_xdata()) and np.max(ln.get_xdata()) <= xb
            assert ya <= np.min(ln.get_ydata()) and np.max(ln.get_ydata()) <= yb
    table = " ".join(t.get_text() for a in fig.axes for t in a.texts)
    for k in (1, 7, 24):
        assert f"{modes.omega_undamped[k - 1]:.4g}" in table, f"mode {k} missing from the table"


def test_a_tow_angle_is_the_rest_shape_of_a_two_dof_mode(tmp_path, figures):
    """Wang's 2-DOF cable towed at 56 deg: its body at (-L sin 56, L cos 56) at rest."""
    L, a = 100.0, np.radians(56.0)
    rest = SimpleNamespace(output_labels=("x_b", "y_b"), y0=np.array([-L * np.sin(a), L * np.cos(a)]),
                           Cq=np.array([[-L * np.cos(a), -np.sin(a)], [-L * np.sin(a), np.cos(a)]]))
    w = np.array([0.3, 8.0])
    modes = Modes(q_labels=("phi", "u"), omega_undamped=w, shapes=np.eye(2), omega_damped=w, omega_natural=w,
                  damping_ratio=np.array([0.1, 0.01]), eigenvalues=1j * w)
    linear_plots.plot_modes(modes, rest, tmp_path / "m.png")
    ax = [a for a in figures[0].axes if a.get_title().startswith("mode 1")][0]
    rest_line = [ln for ln in ax.lines if ln.get_label() == "at rest"][0]
    np.testing.assert_allclose(rest_line.get_xydata()[-1], [-L * np.sin(a), L * np.cos(a)])
    moved = [ln for ln in ax.lines if ln.get_label() == "+ mode"][0].get_xydata()[-1]
    # the pendulum mode moves the body across the cable (along e_n = (-cos, -sin)), 10 % of the extent
    d = moved - rest_line.get_xydata()[-1]
    assert abs(np.dot(d, [np.sin(a), -np.cos(a)])) < 1e-9 * L and np.hypot(*d) == pytest.approx(0.1 * L * np.sin(a))


def _oscillator_rao(omega, wn=6.3, zeta=0.02):
    """Base-excited oscillator y_b / y_s = (wn^2 + 2 i zeta wn w) / (wn^2 - w^2 + 2 i zeta wn w)."""
    h = (wn**2 + 2j * zeta * wn * omega) / (wn**2 - omega**2 + 2j * zeta * wn * omega)
    values = np.zeros((omega.size, 1, 2), complex)
    values[:, 0, 1] = h
    values[:, 0, 0] = 1e-3 * h            # a small surge coupling: drawn on its own figure only
    return RAO(omega=omega, output_labels=("y_b",), input_labels=("x_s", "y_s"), values=values)


def test_rao_axes_frame_the_sea_and_the_modes_it_excites(tmp_path, figures):
    """A 17-mode segmented cable in a 0.4-1.5 rad/s sea on a 0.07-700 rad/s grid: the x axis spans the sea
    band and the modes up to 10 x its top (3 x margin), the y axis the response there, the legend sits
    right of the axes with every mark, and the modes above are named in a note."""
    omega = np.geomspace(0.07, 700.0, 800)
    natural = {f"mode {k + 1} (x[{k}])": w for k, w in enumerate(
        [0.1, 0.4, 0.8, 1.2, 6.3, 9.0, 20.0] + list(np.geomspace(40.0, 650.0, 10)))}
    forcing = {"sea peak 0.628 rad/s (T_p = 10 s)": 0.628, "sea band low": 0.4, "sea band high": 1.5}
    linear_plots.plot_rao_bode({"exact linearization": _oscillator_rao(omega)}, "y_b", "y_s", natural,
                               tmp_path / "rao.png", forcing=forcing)
    fig = figures[0]
    amp, phase = fig.axes[:2]
    x0, x1 = amp.get_xlim()
    assert x0 == pytest.approx(max(omega[0], 0.1 / 3)) and x1 == pytest.approx(9.0 * 3), (x0, x1)   # within the grid
    curve = amp.lines[0]
    inside = (curve.get_xdata() >= x0) & (curve.get_xdata() <= x1)
    y0, y1 = amp.get_ylim()
    peak = np.nanmax(curve.get_ydata()[inside])
    assert y0 <= 1.0 <= y1 and peak <= y1 and y0 >= 1e-5 * peak, (y0, y1, peak)
    legend = amp.get_legend()
    fig.canvas.draw()
    assert legend.get_window_extent().x0 >= amp.get_window_extent().x1 - 1, "the legend covers the curve"
    assert len(legend.get_texts()) <= 6
    _assert_legend_complete(amp)
    note = " ".join(t.get_text() for t in phase.texts)
    assert "10 more modes from 40 to 650 rad/s" in note, note
    assert "6.3 rad/s" in note and "1.2 rad/s" in note, note       # the excited modes are in the table
    # 20 rad/s is above what the sea excites (10 x 1.5 rad/s) but inside the axis: a peak there is marked
    marked = {float(ln.get_xdata()[0]) for ln in amp.lines if ln.get_label() != "exact linearization"}
    assert {0.1, 0.4, 0.8, 1.2, 6.3, 9.0, 20.0} <= marked and not any(w >= 40.0 for w in marked)


def test_rao_fps_label(tmp_path, figures):
    omega = np.geomspace(0.1, 30.0, 200)
    linear_plots.plot_rao_bode({"exact linearization": _oscillator_rao(omega)}, "y_b", "y_s", {"omega_u": 6.3},
                               tmp_path / "r.png", units="fps")
    amp = figures[0].axes[0]
    assert amp.get_ylabel().endswith("[ft/ft]")
    # ft per ft is m per m: the same numbers
    assert np.nanmax(amp.lines[0].get_ydata()) == pytest.approx(np.max(np.abs(_oscillator_rao(omega).values[:, 0, 1])))


def test_a_taut_line_keeps_its_tension_detail(tmp_path, figures):
    """Tensions of 0.125-0.130 N never near slack: the axis spans them (not 0-0.13 N, which would
    flatten a 4 % swing into the top strip)."""
    t = np.linspace(0.0, 20.0, 401)
    wave = np.sin(2 * np.pi * t / 5.5)
    run = _run(t, tension_top=0.1275 + 0.0025 * wave, tension_bottom=0.111 + 0.002 * wave, phi=0.03 * wave,
               u=7e-5 * wave, x_b=0.07 * wave, y_b=2.74 + 0.06 * wave)
    td_plots.plot_time_series(run, tmp_path / "taut.png")
    lo, hi = _axis(figures[0], "tension").get_ylim()
    assert 0.105 < lo < 0.109 and 0.13 < hi < 0.135, (lo, hi)


def test_a_rigid_bodys_attitude_is_drawn_in_degrees_beside_the_swing(tmp_path, figures):
    """A rigid body's roll, pitch and yaw (rad in the run: roll_b, theta_b, yaw_b) are drawn in degrees on the swing
    panel of a chain's figure, named apart from the cable's phi, every mark in its legend."""
    run = _snapping_lift()
    w = 2 * np.pi * run.time / 6.0
    run.data.update(roll_b=0.1 * np.sin(w), theta_b=-0.3 + 0.05 * np.cos(w), yaw_b=np.full_like(w, 0.2))
    td_plots.plot_time_series(run, tmp_path / "rigid.png")
    ax = _axis(figures[0], "body attitude")
    drawn = {ln.get_label().split(":")[0]: ln.get_ydata() for ln in ax.lines}
    np.testing.assert_allclose(drawn["body roll"], np.degrees(0.1 * np.sin(w)))
    np.testing.assert_allclose(drawn["body pitch"], np.degrees(-0.3 + 0.05 * np.cos(w)))
    assert np.degrees(0.2) == pytest.approx(drawn["body yaw"][0])          # steady: one flat line at its value
    assert any(k.startswith("cable $\\phi$") for k in drawn)
    _assert_legend_complete(ax)


def test_a_systems_rigid_body_gets_an_attitude_panel(tmp_path, monkeypatch):
    """A system's figure (lines joined at points) draws every rigid body point's roll, pitch and yaw in degrees on a
    panel of their own (point.NAME.theta_b ... in the run), and none without a rigid body."""
    import cablesys.plots.system as sys_plots
    seen = []
    monkeypatch.setattr(sys_plots, "save_figure", lambda fig, path, **kw: seen.append(fig) or path)
    t = np.linspace(0.0, 30.0, 301)
    w = 2 * np.pi * t / 10.0
    data = {"line.a.tension_from": 4e3 + 500 * np.sin(w), "line.a.tension_to": 3.5e3 + 500 * np.sin(w)}
    for k, (x, y) in enumerate([(0.3 * np.sin(w), 0.0 * w), (0.2 * np.sin(w), 10.0 + 0 * w), (0.1 * np.sin(w), 20 + 0 * w)]):
        data[f"node_x[{k}]"], data[f"node_y[{k}]"] = x, y
    lines, points = {"a": ([0, 1, 2], "ship", "pkg")}, {"ship": ("prescribed", 0), "pkg": ("body", 2)}
    sys_plots.plot_system_series(TimeResult(time=t, data=dict(data), scene_name="synthetic"), tmp_path / "a.png",
                                 lines=lines, points=points)
    assert not [a for a in seen[0].axes if "attitude" in a.get_title()]
    data["point.pkg.theta_b"] = -0.2 + 0.05 * np.sin(w)
    sys_plots.plot_system_series(TimeResult(time=t, data=data, scene_name="synthetic"), tmp_path / "b.png",
                                 lines=lines, points=points)
    ax = _axis(seen[1], "attitude")
    (line,) = [ln for ln in ax.lines if ln.get_label() == "pkg pitch"]
    np.testing.assert_allclose(line.get_ydata(), np.degrees(data["point.pkg.theta_b"]))
    _assert_legend_complete(ax)
    # two points at one place (a package above its sinker, seen from above): their names one under the other
    data["node_x[3]"], data["node_y[3]"] = data["node_x[2]"], data["node_y[2]"]
    sys_plots.plot_system_series(TimeResult(time=t, data=data, scene_name="synthetic"), tmp_path / "c.png",
                                 lines=lines, points={**points, "sinker": ("fixed", 3)})
    notes = {a.get_text(): a.xyann for a in _axis(seen[2], "shape").texts}
    assert notes["pkg (body)"][1] - notes["sinker (fixed)"][1] >= 8
