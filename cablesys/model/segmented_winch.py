"""The winch in the segmented cable: the first section's unstretched length L(t) changes in time.

A ``[winch]`` (:class:`cablesys.scene.ends.Winch`) pays the first section out at its top (node 0, the
sheave) at the prescribed rate w(t) = L'(t) (:func:`cablesys.scene.ends.legs_profile`: payout, hold, haul-in legs, L(0) = l_0 of
Wang 1971 eq. 1). The formulation (no remeshing, differentiable in every parameter, so that an optimal control
can drive L later):

- The N elements of the section share L uniformly: element k spans the unstretched arc sigma from the body in
  [(N - k - 1) L / N, (N - k) L / N], so node j (0 = the sheave, N = the body) sits at the material point
  sigma_j = c_j L, c_j = (N - j) / N. The element's zero-tension length is h_0 = L / N, its reference length
  h_r = h_0 l_r / l_0, its mass m_r h_r and weight in water w_r h_r (Wang 1971 eq. 1, 5, 12 with l_0 -> L):
  the cable in the water has mass m_r l_r L / l_0 (m_r L when T_r = 0), the cable paid out. Equivalently the
  section's parameters are Wang's with l_r -> l_r L / l_0 (:func:`section_with_length`, as
  :mod:`.winch` does for the 2-DOF model: k = (AE)_r / l_r becomes k_r l_0 / L).
- A node is not a material point: sigma_j changes at c_j w. The material velocity at node j of element k is
  dr/dt at fixed sigma = v_j - sigma_j' dr/dsigma = v_j + c_j w (r_b - r_a) / h_0 (in the element the material
  lies uniformly stretched along r_b - r_a; dr/dsigma points from the body to the top, hence the sign). At the
  sheave (c = 1) it is the top's velocity plus w l_e / h_0 along the element: the speed a = w l / L at which
  :mod:`.winch` lets the paid-out cable leave the sheave. The element's terms (:func:`.segmented_element.element_terms`)
  are evaluated with these material end velocities, so that the Voigt damping acts on the material strain
  rate (l_e' - w l_e / L) / h_r (the time derivative of l_e / h_0 at fixed sigma; Wang 1971 eq. 46) and the
  drag on the material's velocity relative to the fluid (eq. 42, 44: the tangential drag sees the cable
  sliding through the water, the normal drag is unchanged since the convection is axial); the added mass
  acts on the normal part of the velocity, which the axial convection does not change (eq. 23-24).
- Lagrange's equations (Wang 1971 eq. 8-9) with L a prescribed coordinate like the top motion
  (:func:`.lagrange.lagrange_equations`: z = L, z' = w, z'' = alpha), element by element as in
  :func:`.segmented_element.element_inertia`: K_e is the element's lumped kinetic energy with the material
  velocities, so f gains -(d2K_e/dv dL) w - (d2K_e/dv dw) alpha: the inertia of the cable accelerated along
  itself by the winch (alpha), of its growing mass and of the convection (w). The mass matrix is the fixed
  model's (the convection is linear in w and does not enter d2K/dv2).
- The top tension (the cable's pull on the sheave) lumps the sheave's half element with its material
  acceleration (:meth:`Payout.top_acceleration`): accelerating the payout at alpha loads the sheave with
  W_b + w L - (M_b + m_r L) alpha for a rigid line (tests/test_segmented_winch.py).
- The element's stretch is uniform, so the material strain rate it sees lacks the convection of the strain
  along the cable (-sigma' d(lambda)/d(sigma), the material moving into a more stretched element): in a steady
  payout the Voigt force of an element is off by at most C_I w w_r / AE (N; 0.4 N for C_I / AE = 0.05 s,
  w = 1 m/s, w_r = 8 N/m), first order in w.
- Neglected, as in :mod:`.winch`: the momentum carried in or out with the paid-out cable at the sheave (a mass
  flux m_r w at the material velocity there, forces of order m_r w (w + |v_top|): for a 30 mm wire, m_r = 3.6
  kg/m, at w = 1 m/s and a 1 m/s heave a few N against 10^4 N of tension) and Lagrange's variable-mass
  correction of the same order. At w = alpha = 0 and L = l_0 every term is the fixed-length model's.

Forces in N, lengths in m, speeds in m/s. The winch's outputs (:data:`WINCH_OUTPUTS`): ``winch_length`` L (m),
``winch_speed`` w (m/s, + pays out), ``winch_acceleration`` alpha (m/s^2), ``winch_power`` T_top w (W, positive
while paying out under tension: the drum is braked; the motor supplies -P while hauling in), T_top the cable's
pull on the sheave (``tension_top``).
"""

from __future__ import annotations

import dataclasses

import casadi as ca

from .section import SectionParameters
from .segmented_element import element_terms, lump_kinetic

__all__ = ["WINCH_OUTPUTS", "Payout", "payout"]

WINCH_OUTPUTS = ("winch_length", "winch_speed", "winch_acceleration", "winch_power")


def section_with_length(P: SectionParameters, L) -> SectionParameters:
    """Section parameters with zero-tension length L in place of l_0: l_r -> l_r L / l_0 (so l_0 = l_r (1 - T_r /
    (AE)_r) -> L, k -> k_r l_0 / L, mass m_r l_r -> m_r l_r L / l_0, weight likewise; d_0 unchanged; Wang 1971 eq. 1-7, 12)."""
    return dataclasses.replace(P, l_r=P.l_r * L / P.l_0)


def material_velocities(c_a, c_b, w, L, n_el: int, ra, va, rb, vb) -> tuple:
    """The material velocities at an element's ends, v + c w (r_b - r_a) / h_0 with h_0 = L / N (module docstring)."""
    dim = len(ra)
    g = w * n_el / L
    return (tuple(va[j] + c_a * g * (rb[j] - ra[j]) for j in range(dim)),
            tuple(vb[j] + c_b * g * (rb[j] - ra[j]) for j in range(dim)))


@dataclasses.dataclass(frozen=True)
class Payout:
    """The first section's prescribed zero-tension length L (m), payout speed w (m/s), acceleration alpha (m/s^2): SX of (t, p)."""

    L: ca.SX
    w: ca.SX
    alpha: ca.SX

    def section(self, P: SectionParameters) -> SectionParameters:
        """The section's parameters at L(t)."""
        return section_with_length(P, self.L)

    def velocities(self, k: int, n_el: int, ra, va, rb, vb) -> tuple:
        """Material velocities at the ends of element k (0 at the sheave) of the N = ``n_el`` elements."""
        return material_velocities((n_el - k) / n_el, (n_el - k - 1) / n_el, self.w, self.L, n_el, ra, va, rb, vb)

    def node_velocity(self, j: int, n_el: int, r_prev, v, r_next) -> tuple:
        """The material velocity at node j (0 < j < N) of the N = ``n_el`` elements, the mean of its two elements'
        (:func:`material_velocities`): v_j + c_j g (r_(j+1) - r_(j-1)) / 2, c_j = (N - j) / N, g = w N / L. The velocity
        the seabed resists (:mod:`.segmented_seabed`): where the winch hauls a laid line in, the node slides along the
        bed and the material on it need not."""
        c = (n_el - j) / n_el * self.w * n_el / self.L
        return tuple(v[i] + 0.5 * c * (r_next[i] - r_prev[i]) for i in range(len(v)))

    def sliding(self, node_r, node_v, seq) -> list:
        """The velocities the seabed resists at every node (:mod:`.segmented_seabed`): ``node_v`` with the paid-out
        section's inner nodes ``seq[1:-1]`` (``seq`` its nodes from the sheave on) at their material velocity
        (:meth:`node_velocity`)."""
        seq, slide = list(seq), list(node_v)
        n_el = len(seq) - 1
        for m in range(1, n_el):
            j = seq[m]
            slide[j] = self.node_velocity(m, n_el, node_r[seq[m - 1]], node_v[j], node_r[seq[m + 1]])
        return slide

    def outputs(self, tension_top) -> list:
        """The values of :data:`WINCH_OUTPUTS`: L (m), w (m/s), alpha (m/s^2) and the power T_top w (W), ``tension_top``
        the cable's pull on the sheave (N)."""
        return [self.L, self.w, self.alpha, tension_top * self.w]

    def top_acceleration(self, n_el: int, r0, v0, a0, r1, v1) -> tuple:
        """The acceleration of the cable at the sheave, the rate of its material velocity v_0 + g (r_1 - r_0) there
        (g = w N / L, module docstring) with the node at the sheave: a_0 + g' (r_1 - r_0) + g (v_1 - v_0),
        g' = N (alpha / L - w^2 / L^2). Its half element's inertia loads the sheave (the top tension), not a_0's;
        the change of the material point at the sheave (the mass flux) is neglected as in the module docstring."""
        g = self.w * n_el / self.L
        gd = n_el * (self.alpha / self.L - self.w ** 2 / self.L ** 2)
        return tuple(a0[j] + gd * (r1[j] - r0[j]) + g * (v1[j] - v0[j]) for j in range(len(r0)))

    def inertia(self, P: SectionParameters, n_el: int, p, rho, t, env, depth0, n_points, dim: int = 2) -> ca.Function:
        """``(r_a, r_b, v_a, v_b, p, z) -> (M_a, M_b, f_a, f_b)`` with z = (L, w, alpha, c_a, c_b): Lagrange's
        equations of one element's lumped kinetic energy with the material velocities, L prescribed
        (:func:`.segmented_element.element_inertia` with z, z', z'' = L, w, alpha; module docstring). ``P`` the
        section's parameters at its reference length (not yet at L)."""
        ra, rb, va, vb = (ca.SX.sym(name, dim) for name in ("ra", "rb", "va", "vb"))
        u = ca.SX.sym("u", dim)
        Ls, ws, als, c_a, c_b = (ca.SX.sym(n) for n in ("L", "w", "alpha", "c_a", "c_b"))
        cols = lambda s: tuple(s[j] for j in range(dim))
        zero = (0.0,) * dim
        vam, vbm = material_velocities(c_a, c_b, ws, Ls, n_el, zero, cols(va), cols(u), cols(vb))
        el = element_terms(section_with_length(P, Ls), n_el, zero, vam, cols(u), vbm, rho=rho, t=t, env=env,
                           depth0=depth0, n_points=n_points)
        K = lump_kinetic(el, vam, vbm)
        v = ca.vertcat(va, vb)
        mom = ca.gradient(K, v)
        M = ca.jacobian(mom, v)
        dK = ca.gradient(K, u)
        f = (ca.vertcat(-dK, dK) - ca.jtimes(mom, u, vb - va)          # eq. 8-9, K_e of the chord u = r_b - r_a
             - ca.jacobian(mom, Ls) * ws - ca.jacobian(mom, ws) * als)  # L prescribed (lagrange.py)
        f = ca.substitute(f, u, rb - ra)
        M = ca.substitute(M, u, rb - ra)
        z = ca.vertcat(Ls, ws, als, c_a, c_b)
        return ca.Function("winch_element_inertia", [ra, rb, va, vb, p, z],
                           [M[:dim, :dim], M[dim:, dim:], f[:dim], f[dim:]])

    def z(self, k: int, n_el: int):
        """The prescribed inputs z = (L, w, alpha, c_a, c_b) of element k's :meth:`inertia`."""
        return ca.vertcat(self.L, self.w, self.alpha, (n_el - k) / n_el, (n_el - k - 1) / n_el)


def payout(scene, layout, P0: SectionParameters, t) -> Payout | None:
    """The first section's L(t) = l_0 + Delta L(t), w(t), alpha(t) (:meth:`cablesys.scene.ends.Winch.profile_at`:
    :func:`~cablesys.scene.ends.legs_profile` on the ``winch.*`` entries of p, t the model's time symbol); None
    without a ``[winch]``."""
    if getattr(scene, "winch", None) is None:
        return None
    dL, w, alpha = scene.winch.profile_at(t, layout.sym, fmin=ca.fmin, fmax=ca.fmax)
    return Payout(L=P0.l_0 + dL, w=w, alpha=alpha)
