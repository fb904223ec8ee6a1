"""Prescribed top motion x_s(t), y_s(t) and its first two derivatives, as a CasADi function.

Sinusoids a sin(omega t + phase) (Wang 1971, "an arbitrary number of sinusoidal functions")
plus an optional sampled series (the report's "non-periodic motions") interpolated by the
not-a-knot cubic spline through the samples (the spline of ``scipy.interpolate.
make_interp_spline``, held at its end values outside the sampled span).

The spline is evaluated at a cost independent of the number of samples, and the
model stays SX and compilable:

- the second derivatives M_i at the samples solve the not-a-knot moment equations
  (de Boor, *A Practical Guide to Splines*, ch. IV), a tridiagonal system once the two end
  conditions are eliminated (Thomas algorithm, :func:`spline_moments`);
- on the piece [t_i, t_{i+1}] the moment form s = A y_i + B y_{i+1} + ((A^3 - A) M_i +
  (B^3 - B) M_{i+1}) h_i^2 / 6, B = (t - t_i) / h_i, A = 1 - B, is written as the cubic
  s = a_i + b_i u + c_i u^2 + d_i u^3 in u = t - t_i (:func:`piece_coefficients`);
- the piece is found by binary search (CasADi's ``low``) and its coefficients read from a
  constant table, in a small MX function called from the SX expression as one call node
  (:func:`series_lookup`); the cubic in u is SX, so its t-derivatives (velocity,
  acceleration, the event locator's jerk) are plain SX: the table lookup has a structurally
  zero derivative and is called once per evaluation.

The samples are therefore *constants of the model*, not entries of ``p`` (a symbolic sample
vector makes every evaluation O(n): the output depends on all n entries, so a straight-line
SX program needs at least n - 1 operations; the previous telescoping sum cost ~26 operations
per sample and axis, 5.95x the sinusoid run at 242 samples; and CasADi's integrators copy
``p`` into their DAE wrapper at every right-hand side, 13 % of a run with 2 x 2002 entries).
A different series is a different model structure (:func:`cablesys.model.params.structure_of`
includes the values; ``ParameterLayout.series_samples`` gives them to the state scales).
:func:`spline_expression` keeps the O(n) form with symbolic samples, as the reference.

Smooth start: with ``top_motion.ramp_s`` > 0 the whole top motion (sinusoids and series) is
multiplied by the cosine ramp :func:`ramp`; unset, it lasts 3 of the longest forcing periods
(``TopMotion.effective_ramp_s``); 0 is Wang's abrupt start. The ramp makes the static start
consistent: top position, velocity and acceleration are 0 at t = 0, so the steady state at rest
(``time_domain.initial_state``) is an equilibrium of the equations of motion at t = 0 and the
stretch mode is not excited by the start.

History: this used to call CasADi's MX-only ``bspline`` primitive with the coefficients from
``ca.solve(A, samples, "csparse")``. That aborted the process ("double free or corruption",
exit 134) on scenes with slack: the event locator differentiates the top acceleration once
more (d2g/dt2), which makes CasADi differentiate the cubic B-spline to degree 0, and CasADi's
``casadi_nd_boor_eval`` (3.6-3.8.2) writes ``boor[degree - 1]``, i.e. one double *before* its
work vector, when a degree-0 spline is evaluated exactly at an interior knot (an output time
equal to a sample time). The corrupted heap chunk header is detected later by malloc. A
4-sample series has no interior knot, hence no crash. Minimal reproducer (valgrind: "Invalid
write of size 8 ... 8 bytes before a block")::

    t = ca.MX.sym("t"); c = ca.MX.sym("c", 305)
    knots = make_interp_spline(np.linspace(0, 60, 305), np.zeros(305), k=3).t
    s = ca.bspline(t, c, [list(knots)], [3], 1, {})
    d3 = ca.jacobian(ca.jacobian(ca.jacobian(s, t), t), t)
    ca.Function("f", [t, c], [d3])(7.5, np.ones(305))   # 7.5 is an interior knot

No upstream CasADi report of this was found (searched casadi/casadi issues: closest are
#2202, a bspline interpolant segfault fixed in 3.3, and #2547/#2801, NaN results); the
reproducer above is what to file. The SX spline removes the primitive, so the bug cannot be
reached from cablesys.
"""

from __future__ import annotations

import casadi as ca
import numpy as np

from .track_path import path_position, track_symbols


# the exogenous vector of the 3-D equations: the planar EXO_LABELS with the sway z_s after each axis pair
EXO_LABELS_3D = ("t", "x_s", "y_s", "z_s", "x_s_rate", "y_s_rate", "z_s_rate", "x_s_acc", "y_s_acc", "z_s_acc")


def vessel_rotation_labels(axes) -> tuple:
    """Names of the vessel's rotation about the node axes ``axes`` (rad), the top input appended to e after the
    translation's (t, z, z', z''): ``rot_z_s`` ... then the rates ``rot_z_s_rate`` ..., then ``rot_z_s_acc`` ...
    (:func:`top_motion_function`)."""
    names = tuple(f"rot_{a}_s" for a in axes)
    return names + tuple(f"{n}_rate" for n in names) + tuple(f"{n}_acc" for n in names)


def symbolic_type(scene):
    """The symbolic type of the model's functions: always ``ca.SX`` (the series is SX too)."""
    return ca.SX


def _thomas_factors(h):
    """Numeric Thomas factors of the not-a-knot moment system for the interior M_1..M_{n-2}.

    Rows i = 1..n-2: h_{i-1} M_{i-1} + 2 (h_{i-1} + h_i) M_i + h_i M_{i+1} = r_i; the end
    moments are eliminated with the not-a-knot conditions (third derivative continuous at
    t_1 and t_{n-2}): M_0 = (1 + h_0/h_1) M_1 - (h_0/h_1) M_2 and its mirror image.
    Returns (sub, diag, sup) of the reduced tridiagonal matrix and the factors (cp, den).
    """
    m = len(h) - 1                     # number of interior moments (n - 2)
    sub, diag, sup = np.zeros(m), np.zeros(m), np.zeros(m)
    for k in range(m):                 # row for interior sample i = k + 1
        i = k + 1
        sub[k], diag[k], sup[k] = h[i - 1], 2.0 * (h[i - 1] + h[i]), h[i]
    # not-a-knot at the start: substitute M_0 into row 1
    r0 = h[0] / h[1]
    diag[0] += h[0] * (1.0 + r0)
    if m > 1:
        sup[0] -= h[0] * r0
    else:                              # n = 3 cannot happen (>= 4 samples), kept for safety
        diag[0] -= h[0] * r0
    # not-a-knot at the end: M_{n-1} = (1 + h_{n-2}/h_{n-3}) M_{n-2} - (h_{n-2}/h_{n-3}) M_{n-3}
    rn = h[-1] / h[-2]
    diag[-1] += h[-1] * (1.0 + rn)
    if m > 1:
        sub[-1] -= h[-1] * rn
    cp, den = np.zeros(m), np.zeros(m)
    for k in range(m):
        den[k] = diag[k] - (sub[k] * cp[k - 1] if k > 0 else 0.0)
        cp[k] = sup[k] / den[k]
    return sub, den, cp


def spline_moments(times, y):
    """Second derivatives of the not-a-knot cubic spline at ``times`` (works on SX or floats).

    Parameters
    ----------
    times : sequence of float
        Sample times, strictly increasing, at least 4 [s].
    y : sequence (SX or float)
        Sample values.

    Returns
    -------
    list
        M_0 .. M_{n-1}, same type as ``y`` entries.
    """
    t = np.asarray(times, float)
    h = np.diff(t)
    n = t.size
    sub, den, cp = _thomas_factors(h)
    slope = [(y[i + 1] - y[i]) / h[i] for i in range(n - 1)]
    r = [6.0 * (slope[i] - slope[i - 1]) for i in range(1, n - 1)]
    m = n - 2
    d = [None] * m                                     # forward sweep
    for k in range(m):
        d[k] = (r[k] - (sub[k] * d[k - 1] if k > 0 else 0.0)) / den[k]
    M_int = [None] * m                                 # back substitution
    for k in reversed(range(m)):
        M_int[k] = d[k] - (cp[k] * M_int[k + 1] if k < m - 1 else 0.0)
    M0 = (1.0 + h[0] / h[1]) * M_int[0] - (h[0] / h[1]) * M_int[1]
    Mn = (1.0 + h[-1] / h[-2]) * M_int[-1] - (h[-1] / h[-2]) * M_int[-2]
    return [M0] + M_int + [Mn]


def spline_expression(times, y, t):
    """SX expression of the not-a-knot cubic spline through (times, y) at ``t``, held outside.

    ``y`` may be symbolic; the piece is selected without branching by a telescoping sum of
    steps, v(t) = v_0 + sum_i [t >= t_i] (v_i - v_{i-1}), so the cost is O(n) per
    evaluation (~26 operations per sample). The reference form of :func:`series_expressions`
    (which the model uses), kept for symbolic samples.
    """
    tk = np.asarray(times, float)
    n = tk.size
    M = spline_moments(tk, y)
    steps = [t >= tk[i] for i in range(1, n - 1)]      # piece index = sum of steps

    def select(values):                                # value of the piece containing tc
        out = values[0]
        for i, s in enumerate(steps, start=1):
            out = out + s * (values[i] - values[i - 1])
        return out
    h = np.diff(tk)
    t_i = select([float(v) for v in tk[:-1]])
    h_i = select([float(v) for v in h])
    y_i, y_j = select(list(y[:-1])), select(list(y[1:]))
    M_i, M_j = select(M[:-1]), select(M[1:])
    B = (t - t_i) / h_i
    A = 1.0 - B
    inside = A * y_i + B * y_j + ((A ** 3 - A) * M_i + (B ** 3 - B) * M_j) * h_i ** 2 / 6.0
    # held at the end values outside the sampled span; at the end points themselves the
    # one-sided derivatives of the spline are kept (a clamp fmin/fmax would zero them at t_0)
    return ca.if_else(t < tk[0], y[0], ca.if_else(t > tk[-1], y[-1], inside))


def piece_coefficients(times, y) -> np.ndarray:
    """Coefficients of the not-a-knot spline through (times, y) on each piece, numerically.

    Parameters
    ----------
    times : sequence of float
        Sample times, strictly increasing, at least 4 [s].
    y : sequence of float
        Sample values.

    Returns
    -------
    numpy.ndarray
        Shape (n - 1, 4): (a_i, b_i, c_i, d_i) with s(t) = a_i + b_i u + c_i u^2 + d_i u^3,
        u = t - t_i on [t_i, t_{i+1}]: the moment form (module docstring) expanded in u,
        a = y_i, b = (y_{i+1} - y_i) / h_i - h_i (2 M_i + M_{i+1}) / 6, c = M_i / 2,
        d = (M_{i+1} - M_i) / (6 h_i).
    """
    tk = np.asarray(times, float)
    v = np.asarray(y, float)
    h = np.diff(tk)
    M = np.asarray(spline_moments(tk, v), float)
    b = np.diff(v) / h - h * (2.0 * M[:-1] + M[1:]) / 6.0
    return np.column_stack([v[:-1], b, M[:-1] / 2.0, np.diff(M) / (6.0 * h)])


def series_lookup(times, columns) -> ca.Function:
    """``lookup(t) -> (t - t_i, coefficients of piece i)`` by binary search in a constant table.

    MX function (CasADi's ``low`` finds i with t_i <= t < t_{i+1}, clamped to the first and
    last piece; the coefficients are read with a symbolic index); meant to be called from SX
    as one call node (``never_inline``). Its output does not depend on t structurally, so
    differentiating the caller with respect to t adds no call.

    Parameters
    ----------
    times : sequence of float
        Sample times (n) [s].
    columns : sequence of numpy.ndarray
        Per-piece tables, each of length n - 1 (e.g. the columns of :func:`piece_coefficients`).

    Returns
    -------
    casadi.Function
        ``t -> [t - t_i, columns[0][i], columns[1][i], ...]`` (a column vector).
    """
    t = ca.MX.sym("t")
    tk = np.asarray(times, float)
    grid = ca.MX(ca.DM(tk))
    i = ca.low(grid, t)
    # one row-major table: a piece's entries are adjacent in memory (one or two cache lines)
    table = np.column_stack([np.asarray(c, float) for c in columns])
    m = table.shape[1]
    flat = ca.MX(ca.DM(table.ravel()))
    # u = t - t_i is computed here, not in the caller: CasADi 3.8.2's SX call node, when
    # differentiated, reads an output whose forward derivative has no structural nonzero as
    # NaN (not 0); with u among the outputs the derivative has one (du/dt = 1)
    rows = [t - grid[i]] + [flat[m * i + j] for j in range(m)]
    return ca.Function("top_series_lookup", [t], [ca.vertcat(*rows)], ["t"], ["piece"])


def series_expressions(times, values, t) -> list:
    """SX expressions of the not-a-knot cubic splines through (times, values[j]) at ``t``.

    Same spline as :func:`spline_expression` (equal to rounding), held at the end values
    outside the sampled span, at a cost independent of the number of samples: one table
    lookup (:func:`series_lookup`) shared by all series, then a cubic in u = t - t_i.

    Parameters
    ----------
    times : sequence of float
        Sample times, strictly increasing, at least 4 [s].
    values : sequence of sequence of float
        One sample sequence per series (numbers: they become constants of the expression).
    t : casadi.SX
        Time symbol.

    Returns
    -------
    list of casadi.SX
        One expression per series.
    """
    tk = np.asarray(times, float)
    coeffs = [piece_coefficients(tk, v) for v in values]
    lookup = series_lookup(tk, [c[:, j] for c in coeffs for j in range(4)])
    piece = lookup.call([t], False, True)[0]                 # never inlined: one call node
    u = piece[0]                                            # t - t_i
    out = []
    for j, v in enumerate(values):
        a, b, c, d = (piece[1 + 4 * j + m] for m in range(4))
        inside = a + u * (b + u * (c + u * d))
        out.append(ca.if_else(t < tk[0], float(v[0]), ca.if_else(t > tk[-1], float(v[-1]), inside)))
    return out


def ramp(t, ramp_s):
    """Smooth-start factor r(t) = u - sin(2 pi u) / (2 pi), u = t / ramp_s, on [0, ramp_s]; 0 before, 1 after.

    A cosine ramp whose *rate* is the raised cosine r' = (1 - cos(2 pi u)) / ramp_s: r, r' and
    r'' vanish at t = 0, and r' and r'' at t = ramp_s, so the top starts at rest with zero
    velocity *and acceleration* and joins the full motion without a jump in acceleration (a
    plain (1 - cos(pi u)) / 2 ramp still jumps in acceleration at t = 0, which rings the
    undamped stretch mode). Multiplies every top-motion amplitude. ``ramp_s = 0``: r = 1.
    """
    u = ca.fmin(ca.fmax(t / ca.fmax(ramp_s, 1e-300), 0.0), 1.0)
    return ca.if_else(ramp_s > 0, u - ca.sin(2 * np.pi * u) / (2 * np.pi), 1.0)


def top_motion_function(scene, layout) -> ca.Function:
    """``top(t, p) -> (t, x_s, y_s, x_s', y_s', x_s'', y_s'')`` for the scene's top motion.

    A 3-D scene (``scene.three_d``) adds the sway z_s (``top_motion.z`` sinusoids):
    ``(t, x_s, y_s, z_s, x_s', y_s', z_s', x_s'', y_s'', z_s'')`` (:data:`EXO_LABELS_3D`); the
    sampled series moves x and y only. A track other than the circle (whose sinusoids are among x and z) adds its
    path (:func:`.track_path.path_position`; in the plane only x: a straight track along +x), after the smooth start,
    which a track has none of. A vessel moving several prescribed points (``scene.vessel_rotation_axes``) appends its
    small rotation theta about those node axes, its rate and acceleration (:func:`vessel_rotation_labels`; the
    sinusoids ``top_motion.vessel.rotation_x[k]`` ..., scene/vessel.py), with the same smooth start: the model moves
    each point by s_0 + theta x Delta.
    """
    t = ca.SX.sym("t")
    p = ca.SX.sym("p", len(layout))
    sym = lambda label: p[layout.index(label)]

    def sines(prefix, n):                     # sum_k a_k sin(w_k t + ph_k) of the terms prefix[k]
        s = ca.SX(0)
        for k in range(n):
            a, w, ph = (sym(f"{prefix}[{k}].{name}") for name in ("amplitude", "frequency", "phase"))
            s = s + a * ca.sin(w * t + ph)
        return s
    pos = [sines(f"top_motion.{axis}", len(getattr(scene.top_motion, axis)))
           for axis in (("x", "y", "z") if scene.three_d else ("x", "y"))]
    series = scene.top_motion.series
    if series is not None:
        # the samples are constants of the model (module docstring): O(1) per evaluation
        spl = series_expressions(series.times, (series.x, series.y), t)
        pos = [pos[j] + spl[j] for j in range(2)] + pos[2:]
    if "top_motion.ramp_s" in layout.labels:
        pos = [ramp(t, sym("top_motion.ramp_s")) * v for v in pos]
    track = scene.top_motion.track
    if track is not None and not track.is_circle:     # a path in the horizontal plane (track_path.py), not ramped
        xz = path_position(t, *track_symbols(track, sym))
        pos = [pos[0] + xz[0]] + pos[1:2] + ([pos[2] + xz[1]] if scene.three_d else [])
    pos = ca.vertcat(*pos)
    vel = ca.jacobian(pos, t)
    acc = ca.jacobian(vel, t)
    out = [t, pos, vel, acc]
    axes = getattr(scene, "vessel_rotation_axes", ())
    if axes:                 # the vessel's rotation (rad), ramped as its translation (:func:`vessel_rotation_labels`)
        rot = [sines(f"top_motion.vessel.rotation_{axis}", len(scene.top_motion.vessel_rotation[axis])) for axis in axes]
        if "top_motion.ramp_s" in layout.labels:
            rot = [ramp(t, sym("top_motion.ramp_s")) * v for v in rot]
        rot = ca.vertcat(*rot)
        rate = ca.jacobian(rot, t)
        out += [rot, rate, ca.jacobian(rate, t)]
    return ca.Function("top", [t, p], [ca.vertcat(*out)], ["t", "p"], ["e"])
