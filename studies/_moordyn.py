"""MoorDyn v2 (the ``moordyn`` wheel, optional ``bench`` extra) as a side-by-side peer.

Translates a one-section cablesys scene (Wang 1971 notation, SI) into a MoorDyn v2 input
file: one line of ``N`` segments between a coupled top point (the ship, moved by the scene's
sinusoids) and a free point (the body), and runs it. MoorDyn is a benchmark and a sanity
check, not the truth (our truth is convergence, closed forms and published data).

The mapping of the cable's numbers (MoorDyn's line is described per *unstretched* length l_0,
Wang's at the reference tension, eq. 1-7):
- EA_md = (AE)_r l_0 / l_r, so that the spring constant EA_md / l_0 equals k = (AE)_r / l_r;
- mass per unstretched length m_r l_r / l_0 (the same total mass, eq. 5);
- MoorDyn's buoyancy comes from its "volume-equivalent" diameter d_v: we choose d_v so that the
  weight in water equals Wang's W_c = w_r l_r (eq. 12), then rescale the coefficients that
  MoorDyn multiplies by d_v: C_dn = C_D d_r / d_v (eq. 42), C_a = gamma d_r^2 / d_v^2 (eq. 23),
  C_dt = C_t d_r / (pi d_v) (MoorDyn's tangential drag uses the circumference pi d; eq. 44
  uses d);
- internal damping BA = C_I l_0 / l_r (force = BA * strain rate; Wang eq. 46: (C_I/l_r) du/dt);
- the body is a free point with volume V, mass m and added-mass coefficient 1/2 chosen so that
  its weight in water is W_b and its virtual mass M_bv; drag 1/2 rho CdA |v| v (eq. 32).

In three dimensions the top moves in x, y and z (MoorDyn's X, -Z and Y: :func:`moordyn_axes`) and a
current profile with headings becomes MoorDyn-C's ``Currents = 1`` steady profile (:func:`current_option`).
"""

from __future__ import annotations

import contextlib
import math
import os
import tempfile
import time
from pathlib import Path

import numpy as np


@contextlib.contextmanager
def _quiet():
    """MoorDyn writes progress to the C stdout/stderr at every step: send them to /dev/null."""
    saved = [os.dup(1), os.dup(2)]
    null = os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(null, 1)
        os.dup2(null, 2)
        yield
    finally:
        os.dup2(saved[0], 1)
        os.dup2(saved[1], 2)
        for fd in saved + [null]:
            os.close(fd)


def moordyn_input(scene, n_segments: int, dt: float) -> str:
    """The MoorDyn v2 input text for a one-section ``scene`` (sphere body; its current: :func:`current_option`)."""
    if len(scene.sections) != 1:
        raise ValueError("the MoorDyn peer handles one cable section")
    sec = scene.sections[0]
    c, b, env = sec.cable, sec.body, scene.environment
    rho, g = env.density, env.gravity
    l_r = c.length
    l_0 = _unstretched_length(scene)
    mass = c.mass_per_length * l_r / l_0
    buoy_mass = mass - c.weight_per_length * l_r / (g * l_0)        # rho * pi d_v^2 / 4
    if buoy_mass <= 0:
        raise ValueError("the cable's weight in water exceeds its mass times g: no MoorDyn diameter fits")
    d_v = math.sqrt(4 * buoy_mass / (rho * math.pi))
    d_r = c.diameter
    cdn = c.cd_normal * d_r / d_v
    can = c.added_mass_factor * d_r**2 / d_v**2
    cdt = c.ct_tangential * d_r / (math.pi * d_v)
    ea = c.ae * l_0 / l_r
    ba = c.internal_damping * l_0 / l_r
    vol = (b.mass_x - b.weight / g) / (1.5 * rho)
    m_b = b.weight / g + rho * vol
    (x0, y0, z_top), _ = _top(scene, 0.0)
    return f"""--------------------- MoorDyn Input File (written by cablesys studies/_moordyn.py) -----
{scene.name}
---------------------- LINE TYPES --------------------------------------------------
TypeName   Diam     Mass/m     EA     BA/-zeta    EI    Cd     Ca     CdAx    CaAx
(name)     (m)      (kg/m)     (N)    (N-s/-)     (-)   (-)    (-)    (-)     (-)
cable     {d_v:.10g}   {mass:.10g}   {ea:.10g}   {ba:.10g}   0   {cdn:.10g}   {can:.10g}   {cdt:.10g}   0.0
---------------------- POINTS --------------------------------------------------------
ID    Attachment     X       Y     Z      Mass    Volume   CdA     Ca
(#)   (word/ID)      (m)     (m)   (m)    (kg)    (m^3)    (m^2)  (-)
1     Coupled   {x0:.10g}   {y0:.10g}   {z_top:.10g}   0   0   0   0
2     Free      {x0:.10g}   {y0:.10g}   {z_top - l_r:.10g}   {m_b:.10g}   {vol:.10g}   {b.drag_area_normal:.10g}   0.5
---------------------- LINES ----------------------------------------------
ID    LineType   AttachA  AttachB  UnstrLen  NumSegs  LineOutputs
(#)   (name)     (#)      (#)      (m)       (-)      (-)
1     cable      2        1        {l_0:.10g}   {n_segments}   -
---------------------- OPTIONS -----------------------------------------
{dt:.10g}   dtM
{g:.10g}  g
{rho:.10g}     WtrDnsty
{10 * l_r + 100:.10g}      WtrDpth
1.0      dtIC
{max(30.0, 20 * math.sqrt(l_r / g)):.6g}       TmaxIC
0.0001    threshIC
0        writeLog
{current_option(scene)}------------------------- need this line --------------------------------------
"""


def _top(scene, t):
    """Top position (MoorDyn frame: z up) and velocity at time t from the scene's sinusoids,
    times cablesys's smooth-start ramp r = u - sin(2 pi u)/(2 pi), u = t / ramp_s
    (``cablesys.model.top_motion.ramp``), so both codes are driven by the same motion."""
    ramp = scene.top_motion.effective_ramp_s
    r, dr = 1.0, 0.0
    if ramp > 0 and t < ramp:
        u = t / ramp
        r, dr = u - math.sin(2 * math.pi * u) / (2 * math.pi), (1 - math.cos(2 * math.pi * u)) / ramp

    def axis(sines):
        pos = sum(s.amplitude * math.sin(s.frequency * t + s.phase) for s in sines)
        vel = sum(s.amplitude * s.frequency * math.cos(s.frequency * t + s.phase) for s in sines)
        return r * pos, r * vel + dr * pos
    xs, vx = axis(scene.top_motion.x)
    ys, vy = axis(scene.top_motion.y)
    zs, vz = axis(scene.top_motion.z)          # sway: MoorDyn's Y (see moordyn_axes)
    return [xs, zs, -(scene.environment.top_depth + ys)], [vx, vz, -vy]


def _segment_state(moordyn, line, n_segments: int):
    """Signed top and body-end tensions and per-segment strains of MoorDyn's line, in cablesys's
    order (element 0 at the top). MoorDyn's node 0 is the body (AttachA), node N the top; its
    segment force is EA strain (only while stretched) plus BA strain rate (always, also while
    slack: it can push), along the segment's unit vector. ``GetLineFairTen`` is the norm of that
    force, which is never negative and rarely zero: the signed value is its projection on the
    segment. A segment is slack when its length is at most its unstretched length (MoorDyn's own
    rule for a zero elastic tension)."""
    r = np.array([moordyn.GetLineNodePos(line, i) for i in range(n_segments + 1)])
    seg = np.diff(r, axis=0)
    length = np.linalg.norm(seg, axis=1)
    unit = seg / length[:, None]
    top = float(np.dot(moordyn.GetLineNodeTen(line, n_segments), unit[-1]))
    bottom = float(np.dot(moordyn.GetLineNodeTen(line, 0), unit[0]))
    return top, bottom, length[::-1]


def run_moordyn(scene, n_segments: int, dt: float, *, duration: float | None = None,
                output_step: float | None = None, scheme: str = "RK4") -> dict:
    """Run MoorDyn on ``scene``; returns time, body x/y (Wang frame: y down from the top's mean
    depth), signed top and body-end tension (MoorDyn's segment force, elastic plus damping, along
    the segment), the per-segment strain (time x segment, top first) and slack fraction (strain
    <= 0: MoorDyn's elastic tension is zero), the wall time of the stepping and the outputs read at
    every output time (``wall_s``) and of MoorDyn's own steps alone (``step_wall_s``), and whether
    it stayed finite and bounded."""
    import moordyn
    duration = duration or scene.numerics.duration
    h = output_step or scene.numerics.output_step
    n_out = round(duration / h)
    l_seg = _unstretched_length(scene) / n_segments
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "lines.txt"
        path.write_text(scene_input(scene, n_segments, dt))     # a line with other ends: ends_input
        write_current_profile(scene, tmp)
        with _quiet():
            s = moordyn.Create(str(path))
            moordyn.SetDt(s, dt)
            moordyn.SetTimeScheme(s, scheme)
            x, _ = _top(scene, 0.0)
            moordyn.Init(s, x, [0.0, 0.0, 0.0])     # equilibrium with the top at rest (a moving top would be extrapolated)
        line, body = moordyn.GetLine(s, 1), moordyn.GetPoint(s, 2)
        pay = winch_hook(scene, line)           # a [winch]: MoorDyn's length rate, set before each call
        settled = settle_in_current(moordyn, s, body, x, scene, dt)
        T = np.zeros(n_out + 1)
        XB, YB, ZB, TT, TB = (np.zeros(n_out + 1) for _ in range(5))
        TOP = np.zeros((n_out + 1, 3))                        # the coupled (top) node, MoorDyn axes
        strain = np.zeros((n_out + 1, n_segments))
        ok = True
        m = max(1, math.ceil(h / max(dt, 1e-3) - 1e-9))      # coupling calls per output step
        h_c = h / m
        step_wall = 0.0
        wall = time.perf_counter()
        with _quiet():
            for k in range(n_out + 1):
                t = k * h
                if k > 0:
                    # MoorDyn moves a coupled point at the velocity it is given over a call and then
                    # places it at x: the secant velocity makes the two agree (the tangent velocity
                    # would jump the top by ~a w^2 h^2 / 2 per call, more than the Dale cable's stretch).
                    # The path is then piecewise linear: its velocity jumps by ~a w^2 h_c per call and
                    # rings the undamped axial mode, so calls are short (h_c <= 1 ms, or one dtM).
                    t_wall = time.perf_counter()
                    try:
                        for j in range(1, m + 1):
                            x_prev = x
                            x, _ = _top(scene, t - h + j * h_c)
                            if pay:
                                pay(moordyn, t - h + (j - 1) * h_c, h_c)
                            moordyn.Step(s, x, [(b - a) / h_c for a, b in zip(x_prev, x)], t - h + (j - 1) * h_c, h_c)
                    except RuntimeError:          # MoorDyn's own NaN check: the step is unstable
                        ok = False
                        break
                    finally:
                        step_wall += time.perf_counter() - t_wall
                try:
                    pos = moordyn.GetPointPos(body)
                    TT[k], TB[k], length = _segment_state(moordyn, line, n_segments)
                except RuntimeError:              # MoorDyn refuses to report a state that went NaN
                    ok = False
                    break
                T[k], XB[k], YB[k], ZB[k] = t, pos[0], -pos[2] - scene.environment.top_depth, pos[1]
                TOP[k] = moordyn.GetLineNodePos(line, n_segments)
                strain[k] = length / l_seg - 1.0
                if not (np.all(np.isfinite(pos)) and abs(pos[2]) < 10 * scene.sections[0].cable.length + 100):
                    ok = False
                    break
            wall = time.perf_counter() - wall
            moordyn.Close(s)
    n = k + 1
    return {"time": T[:n], "x_b": XB[:n], "y_b": YB[:n], **({"z_b": ZB[:n]} if scene.three_d else {}),
            "top_moordyn_axes": TOP[:n], "tension_top": TT[:n], "tension_bottom": TB[:n],
            "element_strain": strain[:n], "slack_fraction_per_segment": np.mean(strain[:n] <= 0.0, axis=0),
            "settle_s": settled, "wall_s": wall, "step_wall_s": step_wall, "stable": ok and n == n_out + 1, "dt": dt, "scheme": scheme, "n_segments": n_segments}


def _unstretched_length(scene) -> float:
    """l_0 = l_r - T_r / k (Wang eq. 1), MoorDyn's ``UnstrLen``."""
    c = scene.sections[0].cable
    return c.length - c.tension_ref * c.length / c.ae


def axial_step_estimate(scene, n_segments: int) -> float:
    """2.8 / omega_max for the stiffest segment mode (omega_max = 2 sqrt(k_seg / m_node)), the
    explicit RK4 limit on the imaginary axis: where the search for MoorDyn's step starts."""
    c = scene.sections[0].cable
    l_seg = c.length / n_segments
    m_node = (c.mass_per_length + c.added_mass_factor * scene.environment.density * math.pi * c.diameter**2 / 4) * l_seg
    k_seg = c.ae / l_seg
    return 2.8 / (2 * math.sqrt(k_seg / m_node))


def _agree(a: dict, b: dict, scene, tol: float) -> bool:
    """Body motion within ``tol`` of the top amplitude (or of b's range) and top tension within
    ``tol`` of b's largest tension, sample by sample."""
    amp = sum(abs(t.amplitude) for t in scene.top_motion.x + scene.top_motion.y)
    span = max(np.ptp(b["x_b"]), np.ptp(b["y_b"]), amp)
    body = max(np.max(np.abs(a["x_b"] - b["x_b"])), np.max(np.abs(a["y_b"] - b["y_b"]))) / span
    tens = np.max(np.abs(a["tension_top"] - b["tension_top"])) / max(np.max(b["tension_top"]), 1e-300)
    return body <= tol and tens <= tol


def largest_stable_dt(scene, n_segments: int, *, probe_s: float | None = None, scheme: str = "RK4",
                      start: float | None = None, floor: float = 1e-7, tol: float = 0.02, agree=None,
                      runs: dict | None = None, refine: int = 0, trials: list | None = None) -> float:
    """MoorDyn's largest usable step: halving from ``start`` (default 4x the axial estimate), the
    first step whose run over ``probe_s`` (default the scene's duration) stays finite and bounded
    and agrees with the run at half that step within ``tol`` (body motion, top tension). Just
    above RK4's limit on the undamped axial mode MoorDyn stays bounded but its tension is
    chaotic (it goes slack at rest), so boundedness alone is not stability here.

    ``refine`` rounds of geometric bisection then search between the accepted step and the rejected
    one above it (each round the same test at sqrt(lo hi)): the step found is within
    2^(1 / 2^refine) of the largest accepted one instead of within 2x.

    ``agree(a, b) -> bool`` replaces the sample-by-sample test (a slack-and-snap run's transient
    amplifies differences by 1e5 before it settles: compare its settled statistics instead). A
    slack scene must be probed past its smooth start: a probe inside it sees no snap.
    ``runs``, if given, receives the runs made, by step (the caller can reuse the chosen one);
    ``trials``, if given, receives one entry per tested step: {dt_s, stable, agrees, wall_s} (the wall of
    the step's probe run and its half-step run)."""
    dt = start or min(4 * axial_step_estimate(scene, n_segments), 0.05)
    agree = agree or (lambda a, b: _agree(a, b, scene, tol))
    runs = {} if runs is None else runs
    run = lambda h: runs[h] if h in runs else runs.setdefault(h, run_moordyn(scene, n_segments, h, duration=probe_s, scheme=scheme))

    def ok(h) -> bool:
        t0 = time.perf_counter()
        a = run(h)
        good = bool(a["stable"])
        agrees = None
        if good:
            b = run(h / 2)
            agrees = bool(b["stable"] and agree(a, b))
            good = agrees
        if trials is not None:
            trials.append({"dt_s": h, "stable": bool(a["stable"]), "agrees": agrees,
                           "probe_s": probe_s, "wall_s": time.perf_counter() - t0})
        return good

    rejected = None
    while dt >= floor:
        if ok(dt):
            break
        rejected, dt = dt, dt / 2
    else:
        raise RuntimeError(f"MoorDyn found no stable step above {floor} s")
    if rejected is not None:
        lo, hi = dt, rejected
        for _ in range(refine):
            mid = math.sqrt(lo * hi)
            lo, hi = (mid, hi) if ok(mid) else (lo, mid)
        dt = lo
    return dt


# -- other ends (issue 25, studies/_bench_ends.py): an anchor on a seabed, a winch -------------------------------------

def scene_input(scene, n_segments: int, dt: float) -> str:
    """The MoorDyn input of ``scene``: :func:`ends_input` for an anchored line, else :func:`moordyn_input`."""
    return ends_input(scene, n_segments, dt) if scene.anchor is not None else moordyn_input(scene, n_segments, dt)


def volume_diameter(text: str) -> float:
    """MoorDyn's volume-equivalent diameter d_v (m) in an input text of :func:`moordyn_input` (its line type row)."""
    return float(next(line for line in text.splitlines() if line.startswith("cable ")).split()[1])


def seabed_options(scene, n_segments: int, d_v: float) -> dict:
    """MoorDyn v2's seabed options for the scene's flat :class:`cablesys.scene.Seabed` (MoorDyn v2 documentation,
    moordyn.readthedocs.io, Input Files / Options; the law in MoorDyn-C's ``Line::getStateDeriv``).

    MoorDyn's bed pushes a node below ``WtrDpth`` by B_z = (kBot delta - cBot delta') d_v l (d_v its volume-equivalent
    diameter, l half of each adjacent segment's unstretched length), ours by (k delta + c delta') d_0 l
    (:mod:`cablesys.model.segmented_seabed`): kBot = k d_0 / d_v and cBot = c d_0 / d_v give the same force. MoorDyn's
    friction is a saturated linear damping of the node's horizontal speed v, F = mu min(FricDamp |v|, |B_z|)
    (StatDynFricScale = 1: the static and dynamic coefficients equal), ours mu F_n tanh(v / v_s): FricDamp = w l / v_s
    gives the same slope at rest for a node lying on the bed under its own weight in water w l, and both saturate
    at mu times the normal force. Where the laws differ: MoorDyn's normal force is not clipped at zero (its damping
    can pull a rising node into the bed), the friction's knee is sharp (ours reaches 76 % of mu F_n at v = v_s, 96 %
    at 2 v_s), and FricDamp is one number for every node (our slope follows each node's normal force)."""
    bed, sec, c = scene.seabed, scene.sections[0], scene.sections[0].cable
    if bed.slope_deg != 0.0:
        raise ValueError("the MoorDyn peer maps a flat seabed only (WtrDpth); a sloped one needs its bathymetry file")
    d_0 = c.diameter
    return {"WtrDpth": bed.depth, "kBot": bed.stiffness * d_0 / d_v, "cBot": bed.damping * d_0 / d_v,
            "FrictionCoefficient": bed.friction_axial,
            "FricDamp": c.weight_per_length * c.length / n_segments / bed.friction_speed, "StatDynFricScale": 1.0}


def ends_input(scene, n_segments: int, dt: float) -> str:
    """The MoorDyn v2 input of an anchored one-section line on a flat seabed: :func:`moordyn_input`'s line (the same
    mapping of the cable's numbers) with its point 2 fixed at the anchor instead of a free body, and the seabed's
    options (:func:`seabed_options`) in place of the far-away bed."""
    text = moordyn_input(scene, n_segments, dt)
    a, depth0 = scene.anchor, scene.environment.top_depth
    opts = seabed_options(scene, n_segments, volume_diameter(text)) if scene.seabed is not None else {}
    out = []
    for line in text.splitlines():
        if line.startswith("2     Free"):
            line = f"2     Fixed     {a.x:.10g}   0   {-(depth0 + a.y):.10g}   0   0   0   0"
        elif line.split()[-1:] == ["WtrDpth"] and opts:
            line = "\n".join(f"{v:.10g}   {k}" for k, v in opts.items())
        out.append(line)
    return "\n".join(out) + "\n"


def winch_hook(scene, line):
    """None without a ``[winch]``; else ``pay(moordyn, t0, h)``: before a coupling call from t0 over h, the line's
    unstretched length L(t0) = l_0 + Delta L(t0) (:meth:`cablesys.scene.ends.Winch.profile`) and its rate over the
    call, the secant (L(t0 + h) - L(t0)) / h (MoorDyn v2 ``SetLineUnstretchedLength`` / ``...Vel``: within a call
    L = L(t0) + t_local rate, every segment L / N, mass, weight and buoyancy from it: the same uniform share as
    :mod:`cablesys.model.segmented_winch`)."""
    if scene.winch is None:
        return None
    l_0, w = _unstretched_length(scene), scene.winch

    def pay(moordyn, t0, h):
        a, b = l_0 + w.profile(t0)[0], l_0 + w.profile(t0 + h)[0]
        moordyn.SetLineUnstretchedLength(line, a)
        moordyn.SetLineUnstretchedLengthVel(line, (b - a) / h)
        _give_back_none(2)
    return pay


def _give_back_none(k: int) -> None:
    """The moordyn 2.7.2 wheel's SetLineUnstretchedLength and SetLineUnstretchedLengthVel return None without taking
    a reference to it (each call lowers None's reference count by one: CPython 3.11 aborts with "deallocating None"
    after a few thousand calls); give back ``k`` lost references for good (a kept list would drop them at exit)."""
    import ctypes
    for _ in range(k):
        ctypes.pythonapi.Py_IncRef(ctypes.py_object(None))


def moordyn_static(scene, n_segments: int, dt: float = 1e-3) -> dict:
    """MoorDyn's initial equilibrium of ``scene`` (its stationary solver, the top at rest): ``top_force`` the
    magnitude of the force of the line on the top point (N; its end node's weight and drag included, MoorDyn's
    ``GetPointForce`` of the coupled point) and ``top_segment_tension`` the end segment's (N)."""
    import moordyn
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "lines.txt"
        path.write_text(scene_input(scene, n_segments, dt))
        with _quiet():
            s = moordyn.Create(str(path))
            x, _ = _top(scene, 0.0)
            moordyn.Init(s, x, [0.0, 0.0, 0.0])
        line = moordyn.GetLine(s, 1)
        out = {"top_force": float(np.linalg.norm(moordyn.GetPointForce(moordyn.GetPoint(s, 1)))),
               "top_segment_tension": float(np.linalg.norm(moordyn.GetLineNodeTen(line, n_segments)))}
        with _quiet():
            moordyn.Close(s)
    return out


# -- three dimensions (the 3-D cases of bench_vs_moordyn, studies/_bench_3d.py) ------------------------------


def moordyn_axes(r) -> np.ndarray:
    """cablesys (x, y down from the top's mean depth, z) to MoorDyn's (X, Y, Z up from the still surface):
    X = x, Y = z, Z = -(top_depth + y) for ``top_depth`` = 0; both right-handed (e_x x e_y = e_z in
    cablesys, e_y = -E_Z, so e_z = E_Y). The top-depth shift is the caller's (``_top`` adds it)."""
    r = np.asarray(r, float)
    return np.stack([r[..., 0], r[..., 2], -r[..., 1]], axis=-1)


def _has_current(scene) -> bool:
    return any(s != 0.0 for s in scene.environment.current_speeds)


def current_option(scene) -> str:
    """MoorDyn-C's ``Currents`` option line: 1 (a steady current profile read from ``current_profile.txt`` in
    the input file's folder, linear in depth between its points and constant beyond them, as cablesys'
    profile) when the scene has a current, else nothing (MoorDyn's default: still water)."""
    return "1        Currents\n" if _has_current(scene) else ""


def current_profile_text(scene) -> str:
    """MoorDyn's ``current_profile.txt`` for the scene's current: three header lines, then one line per
    profile point ``z ux uy uz`` (z up from the still surface, ascending) with cablesys' speeds c_k along
    their headings h_k (deg from +x towards +z: MoorDyn's ux = c cos h, uy = c sin h; :func:`moordyn_axes`).
    cablesys' current depths are depths below the surface (the element's ``top_depth + y``)."""
    env = scene.environment
    rows = [(-d, c * math.cos(math.radians(h)), c * math.sin(math.radians(h)))
            for d, c, h in zip(env.current_depths, env.current_speeds, env.headings_per_depth_deg)]
    if len(rows) == 1:                       # one point: the same current at every depth
        rows = [(-10 * scene.sections[0].cable.length - 100, *rows[0][1:]), rows[0]]
    body = "\n".join(f"{z:.10g} {ux:.10g} {uy:.10g} 0.0" for z, ux, uy in sorted(rows))
    return ("--------------------- MoorDyn steady currents File (written by cablesys studies/_moordyn.py) -----\n"
            "Tabulated file with the water currents components\nz (m), ux (m/s), uy (m/s), uz (m/s)\n" + body + "\n")


def write_current_profile(scene, folder) -> None:
    """Write ``current_profile.txt`` next to the input file when the scene has a current."""
    if _has_current(scene):
        (Path(folder) / "current_profile.txt").write_text(current_profile_text(scene))


SETTLE_CHUNK_S, SETTLE_MAX_S = 10.0, 5000.0


def settle_in_current(moordyn, system, body, x_top, scene, dt: float, *, rate: float = 1e-5) -> float:
    """Bring MoorDyn to its equilibrium in the scene's current before the run (untimed): its initial equilibrium
    (``Init``) is found in still water (the body starts straight under the top whatever the current; checked: 0.0 m
    offset at t = 0 with ``Currents = 1``), and the line drifts into the current over ~10 time constants of ~130 s
    (300 m wire in 0.5 m/s), where cablesys starts from its statics in the current. The top is held at its t = 0
    position and MoorDyn steps in chunks of ``SETTLE_CHUNK_S`` (times before 0: the steady profile does not depend
    on time) until the body moves less than ``rate`` m/s over a chunk (at most ``SETTLE_MAX_S``). Returns the
    settling time (s; 0 without current, NaN when MoorDyn failed at this step: the run then reports it unstable)."""
    if not _has_current(scene):
        return 0.0
    n = max(1, math.ceil(SETTLE_CHUNK_S / dt - 1e-9))
    h = SETTLE_CHUNK_S / n
    t, before = -SETTLE_MAX_S, np.array(moordyn.GetPointPos(body))
    with _quiet():
        while t < 0.0:
            try:
                for _ in range(n):
                    moordyn.Step(system, x_top, [0.0, 0.0, 0.0], t, h)
                    t += h
                now = np.array(moordyn.GetPointPos(body))
            except RuntimeError:          # an unstable step: the run that follows reports it (not finite)
                return math.nan
            if not np.all(np.isfinite(now)) or np.linalg.norm(now - before) < rate * SETTLE_CHUNK_S:
                break
            before = now
    return t + SETTLE_MAX_S
