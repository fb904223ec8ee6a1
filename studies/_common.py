"""Small helpers shared by the time-domain studies: --out/--quick parsing, JSON writing.

Also the hand-derived NumPy right-hand side of Wang's (1971) 2-DOF model, used by the
benchmark as the "straightforward NumPy" competitor and as an independent cross-check of
the CasADi model (which is derived by automatic differentiation of the same energies).
"""

from __future__ import annotations

import argparse
import json
import math
import os
from pathlib import Path

import numpy as np


# the BDF(<= 2) tolerances the benchmarks try on the segmented model against MoorDyn, loosest first: a row keeps the
# first whose statistics are within matched accuracy of the run's own tight run (bench_vs_moordyn._matched)
BDF_RTOLS = (1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 1e-5, 1e-6)


def parse_args(description: str, argv=None, extra=None) -> argparse.Namespace:
    """--out DIR (created) and --quick; ``extra(parser)`` adds a study's own options."""
    ap = argparse.ArgumentParser(description=description)
    ap.add_argument("--out", required=True, type=Path, help="output directory (created if missing)")
    ap.add_argument("--quick", action="store_true", help="a much shorter run (for tests)")
    if extra is not None:
        extra(ap)
    args = ap.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    return args


def _clean(obj):
    if isinstance(obj, dict):
        return {str(k): _clean(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_clean(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return _clean(obj.tolist())
    if isinstance(obj, (np.floating, float)):
        v = float(obj)
        return v if math.isfinite(v) else None
    if isinstance(obj, np.integer):
        return int(obj)
    if isinstance(obj, np.bool_):
        return bool(obj)
    return obj


def write_json(path: Path, data: dict) -> Path:
    path = Path(path)
    path.write_text(json.dumps(_clean(data), indent=2) + "\n")
    return path


def setup_matplotlib():
    os.environ.setdefault("MPLBACKEND", "Agg")
    import matplotlib
    matplotlib.use(os.environ["MPLBACKEND"])
    import matplotlib.pyplot as plt
    return plt


# ---------------------------------------------------------------------------------------
# Wang (1971) 2-DOF equations of motion, derived by hand (not from the printed S-terms)
# ---------------------------------------------------------------------------------------
#
# q = (phi, u), L = l_0 + u, e_t = (-sin phi, cos phi) down the cable, e_n = (-cos phi, -sin phi);
# de_t/dphi = e_n, de_n/dphi = -e_t. Body: r_b = r_s + L e_t, v_b = v_s + u' e_t + L phi' e_n,
# a_b = a_s + (u'' - L phi'^2) e_t + (L phi'' + 2 u' phi') e_n.
#  * Body kinetic energy (eq. 16) with the diagonal virtual-mass matrix B = diag(M_bx, M_by): its
#    Lagrange terms are J^T B a_b with J = [L e_n, e_t].
#  * Cable kinetic energy (eq. 22, 24) with a = v_s.e_t, b = v_s.e_n (da/dphi = b, db/dphi = -a):
#    K_ct = M_c/2 (a^2 + a u' + u'^2/3), K_cn = M_cv(u)/2 (b^2 + b L phi' + L^2 phi'^2/3).
#    d/dt dK/dq' - dK/dq gives
#      phi: M_cv L^2/3 phi'' + M_cv' u'/2 (b L + 2 L^2 phi'/3) + M_cv/2 (L a_s.e_n + b u' + 4 L u' phi'/3)
#           + M_cv a b - M_c/2 (2 a + u') b
#      u:   M_c/3 u'' + M_c/2 (a_s.e_t + b phi') - M_cv'/2 (b^2 + b L phi' + L^2 phi'^2/3)
#           - M_cv/2 (b phi' + 2 L phi'^2/3)
#  * Potential (eq. 15): dV/dphi = (W_b + W_c/2) L sin phi, dV/du = k u - (W_b + W_c/2) cos phi.
#  * Forces: body drag Q = (L D.e_n, D.e_t) (eq. 37); cable normal drag on N segments with moment
#    arm (i - 1/2) L / N (eq. 43); the whole tangential drag goes to Q_u (eq. 45); Voigt damping (46).

class WangNumpy:
    """NumPy right-hand side x' = F(t, x) of one taut section with a sphere (Dale scene)."""

    def __init__(self, scene):
        c, b, env, top = scene.cable, scene.body, scene.environment, scene.top_motion
        if not b.is_sphere:
            raise ValueError("WangNumpy implements the sphere drag law (eq. 32) only")
        if env.waves or any(v != 0.0 for v in env.current_speeds) or env.system_speed != 0.0:
            raise ValueError("WangNumpy implements still water only (no current, no waves)")
        if top.series is not None:
            raise ValueError("WangNumpy implements sinusoidal top motion only")
        self.k = c.ae / c.length
        self.l0 = c.length - c.tension_ref / self.k
        self.l_r = c.length
        self.p = c.thinning_ratio
        self.d0 = c.diameter * (1 - self.p * c.tension_ref / (self.k * c.length))
        on = 1.0 if c.cable_mass_switch >= 0 else 0.0
        self.mc = c.mass_per_length * c.length * on
        self.wc = c.weight_per_length * c.length
        self.gam_rho = c.added_mass_factor * env.density * math.pi / 4 * on
        self.rho = env.density
        self.cd, self.ct, self.ci = c.cd_normal, c.ct_tangential, c.internal_damping
        self.wb, self.mbx, self.mby, self.cda = b.weight, b.mass_x, b.mass_y, b.drag_area_normal
        self.wsum = self.wb + 0.5 * self.wc
        n = scene.numerics.drag_segments
        self.xi = (np.arange(1, n + 1) - 0.5) / n
        self.n = n
        self.sx = np.array([[s.amplitude, s.frequency, s.phase] for s in top.x]).reshape(-1, 3)
        self.sy = np.array([[s.amplitude, s.frequency, s.phase] for s in top.y]).reshape(-1, 3)
        self.nfev = 0

    @staticmethod
    def _sines(S, t):
        a, w, ph = S[:, 0], S[:, 1], S[:, 2]
        arg = w * t + ph
        return np.sum(a * np.sin(arg)), np.sum(a * w * np.cos(arg)), -np.sum(a * w * w * np.sin(arg))

    def top(self, t):
        """(x_s, y_s), (x_s', y_s'), (x_s'', y_s'') at time t."""
        x, xd, xdd = self._sines(self.sx, t)
        y, yd, ydd = self._sines(self.sy, t)
        return (x, y), (xd, yd), (xdd, ydd)

    def __call__(self, t, x):
        self.nfev += 1
        phi, u, phid, ud = x
        _, vs, acc = self.top(t)
        s, c = math.sin(phi), math.cos(phi)
        et, en = (-s, c), (-c, -s)
        L = self.l0 + u
        a = vs[0] * et[0] + vs[1] * et[1]
        bb = vs[0] * en[0] + vs[1] * en[1]
        ast = acc[0] * et[0] + acc[1] * et[1]
        asn = acc[0] * en[0] + acc[1] * en[1]
        d = self.d0 * (1 - self.p * u / self.l_r)
        dd = -self.d0 * self.p / self.l_r
        mcv = self.mc + self.gam_rho * d * d * L
        mcv_u = self.gam_rho * (2 * d * dd * L + d * d)
        # mass matrix (A1-A3 of eq. 47-48)
        a1 = L * L * (mcv / 3 + self.mbx * c * c + self.mby * s * s)
        a2 = L * s * c * (self.mbx - self.mby)
        a3 = self.mc / 3 + self.mbx * s * s + self.mby * c * c
        # body: J^T B (a_s - L phi'^2 e_t + 2 u' phi' e_n)
        w_t, w_n = -L * phid * phid, 2 * ud * phid
        gx = acc[0] + w_t * et[0] + w_n * en[0]
        gy = acc[1] + w_t * et[1] + w_n * en[1]
        bgx, bgy = self.mbx * gx, self.mby * gy
        r_phi = L * (en[0] * bgx + en[1] * bgy)
        r_u = et[0] * bgx + et[1] * bgy
        # cable
        r_phi += (mcv_u * ud / 2 * (bb * L + 2 * L * L * phid / 3)
                  + mcv / 2 * (L * asn + bb * ud + 4 * L * ud * phid / 3)
                  + mcv * a * bb - self.mc / 2 * (2 * a + ud) * bb)
        r_u += (self.mc / 2 * (ast + bb * phid)
                - mcv_u / 2 * (bb * bb + bb * L * phid + L * L * phid * phid / 3)
                - mcv / 2 * (bb * phid + 2 * L * phid * phid / 3))
        # potential
        r_phi += self.wsum * L * s
        r_u += self.k * u - self.wsum * c
        # body drag (sphere, still water): relative velocity -v_b
        vbx = vs[0] + ud * et[0] + L * phid * en[0]
        vby = vs[1] + ud * et[1] + L * phid * en[1]
        vr = math.hypot(vbx, vby)
        dbx, dby = -0.5 * self.rho * self.cda * vr * vbx, -0.5 * self.rho * self.cda * vr * vby
        q_phi = L * (dbx * en[0] + dby * en[1])
        q_u = dbx * et[0] + dby * et[1]
        # cable drag at segment midpoints (eq. 38-45)
        xi = self.xi
        vqn = -(bb + xi * L * phid)
        vqt = -(a + xi * ud)
        seg = L / self.n
        q_phi += np.sum(xi * L * 0.5 * self.rho * self.cd * d * seg * np.abs(vqn) * vqn)
        q_u += np.sum(0.5 * self.rho * self.ct * d * seg * np.abs(vqt) * vqt)
        q_u += -self.ci / self.l_r * ud
        f1, f2 = q_phi - r_phi, q_u - r_u
        det = a1 * a3 - a2 * a2
        return np.array([phid, ud, (a3 * f1 - a2 * f2) / det, (a1 * f2 - a2 * f1) / det])


def speed_bars(ax, rows, extras=("wang", "auto"), *, cablesys_label: str, title: str, fontsize: int = 8) -> None:
    """Bars of wall time per simulated second, MoorDyn's and cablesys's side by side, per case and N of the
    benchmark rows (``by_n`` entries: ``moordyn_s_per_s``, ``cablesys_s_per_s``, ``speedup``), then per model of
    ``extras`` present in a row (``row[k]["s_per_s"]``, ``row[f"{k}_speedup"]`` against MoorDyn at the row's first
    N), the measured speed-up written over each cablesys bar; a log axis. A row's ``auto_bound`` (its fastest run,
    ``_bench_auto.auto_bound``) marks the auto bar with the least time any stepped auto keeping its tolerance takes."""
    labels, md, cs, ratio, bound = [], [], [], [], {}
    for r in rows:
        for e in r["by_n"]:
            labels.append(f"{r['case']}\nN = {e['segments']}")
            md.append(e["moordyn_s_per_s"])
            cs.append(e["cablesys_s_per_s"] or np.nan)
            ratio.append(e.get("speedup"))
        for k in extras:
            if "s_per_s" in r.get(k, {}):
                n0 = r["by_n"][0]["segments"] if r["by_n"] else "?"      # its speedup is against this MoorDyn run
                labels.append(f"{r['case']}\n{k}\nvs N = {n0}")
                md.append(np.nan)
                cs.append(r[k]["s_per_s"])
                ratio.append(r.get(f"{k}_speedup"))
                fastest = (r.get("auto_bound") or {}).get("fastest") if k == "auto" else None
                if fastest:
                    bound[len(cs) - 1] = fastest["wall_s"] / r["duration_s"]
    x = np.arange(len(labels))
    ax.bar(x - 0.2, md, 0.4, label="MoorDyn v2 (largest stable RK4 step)")
    ax.bar(x + 0.2, cs, 0.4, label=cablesys_label)
    if bound:
        ax.scatter([x[i] + 0.2 for i in bound], [bound[i] for i in bound], marker="_", s=400, color="k", zorder=3,
                   label="auto's bound: the fastest stepped run keeping its tolerance (no choice, no checks)")
    for xi, c, q in zip(x, cs, ratio):
        if q:
            ax.annotate(f"{q:.3g}x", (xi + 0.2, c), textcoords="offset points", xytext=(0, 3), ha="center", fontsize=8)
    ax.set_yscale("log")
    ax.set_xticks(x, labels, fontsize=8)
    ax.set_ylabel("wall time per simulated second (s/s)")
    ax.set_title(title, fontsize=10)
    # under the tick labels, one entry a line: inside, it covered the tallest bars (the steady turn's MoorDyn at
    # N = 20); above, its long entries ran past the figure's edges
    ax.legend(fontsize=fontsize, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=1, frameon=False)
