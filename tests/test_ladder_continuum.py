"""The closed-form cable the ladder's estimates compare against (cablesys/ladder/continuum.py)."""

import math

import numpy as np

from cablesys.ladder.continuum import Member, elements, exact, respond


def _rod(ae=4.0e7, length=300.0, mass=2.5, end=3100.0):
    return Member(length=length, stiffness=complex(ae), mass=mass, drag=0.0, end_mass=end, end_drag=0.0, current=0.0)


def test_exact_member_is_a_spring_with_mass_at_low_frequency():
    # a rod much shorter than its wave: the straight cable's W_b = (k + m L w^2 / 6) / (k - (M + m L / 3) w^2)
    # (consistent mass of the linear shape, Wang 1971 eq. 22-25) to O((kL)^4)
    rod = _rod()
    w = 0.6
    k = rod.stiffness.real / rod.length
    m_eff = rod.end_mass + rod.mass * rod.length / 3
    wb, fb, _ = exact(rod, w, 0.0, 0.0)
    assert abs(wb - (k + rod.mass * rod.length * w**2 / 6) / (k - m_eff * w**2)) < 1e-5 * abs(wb)
    # and the force on the body is its inertia (no damping): F = -M w^2 W_b
    assert abs(fb + rod.end_mass * w**2 * wb) < 1e-9 * abs(fb)


def test_string_resonance_at_its_first_mode():
    # a string fixed at the top with a huge body: first mode at pi / L sqrt(T / m)
    s = Member(length=100.0, stiffness=complex(1e4), mass=2.0, drag=0.0, end_mass=1e12, end_drag=0.0, current=0.0)
    w1 = math.pi / 100.0 * math.sqrt(1e4 / 2.0)
    # the body barely moves and the top force is the fixed-fixed string's: it diverges at w1
    f = [abs(exact(s, w, 1e-6, 0.0)[2]) for w in (0.9 * w1, 0.999 * w1, 1.1 * w1)]
    assert f[1] > 50 * max(f[0], f[2])


def test_lumped_elements_converge_to_the_continuum_at_second_order():
    s = Member(length=100.0, stiffness=complex(1e4), mass=2.0, drag=0.5, end_mass=500.0, end_drag=50.0, current=0.0)
    w = 1.2
    ref = exact(s, w, 0.5, 50.0)[0]
    err = [abs(elements(s, w, 0.5, 50.0, n, consistent=False)[0] - ref) for n in (8, 16, 32)]
    rates = np.log2(np.array(err[:-1]) / np.array(err[1:]))
    assert np.all(np.abs(rates - 2.0) < 0.2), rates
    # one consistent element (the straight cable) is closer than one lumped element
    one = [abs(elements(s, w, 0.5, 50.0, 1, consistent=c)[0] - ref) for c in (True, False)]
    assert one[0] < one[1]


def test_equivalent_drag_damps_a_resonant_response():
    # at the spring-mass resonance the undamped response is unbounded; the body's describing-function
    # drag (8 / 3 pi) 1/2 rho C A |V| bounds it: W_b of order sqrt(k / (rho C A)) / w-ish, finite
    rod = Member(length=10.0, stiffness=complex(1e5), mass=0.0, drag=0.0, end_mass=100.0, end_drag=500.0, current=0.0)
    w = math.sqrt(1e4 / 100.0)
    wb = respond(rod, w, 0.1, "exact")[0]
    # the harmonic balance at resonance: k W_b... = the drag's first harmonic, |W_b|^2 = k X_s / (c' w^2)
    # with c' = (8 / 3 pi) 500 (the inertia cancels the spring), i.e. |W_b| = sqrt(1e4 0.1 / (c' 100))
    c1 = 8 / (3 * math.pi) * 500.0
    assert abs(abs(wb) - math.sqrt(1e4 * 0.1 / (c1 * 100.0))) < 0.01 * abs(wb)


def test_closed_form_element_chain_equals_the_tridiagonal_solve():
    # the recurrence's closed form (continuum.elements) against the node equations solved directly, for the
    # lumped string with drag and the consistent single element, at element counts the estimate tabulates
    from cablesys.ladder.continuum import elements_banded
    s = Member(length=100.0, stiffness=complex(1e4), mass=2.0, drag=0.5, end_mass=500.0, end_drag=50.0, current=0.0)
    for w in (0.3, 1.2, 6.0):
        for n, consistent in ((1, True), (1, False), (2, False), (3, False), (17, False), (128, False)):
            a = elements(s, w, 0.5, 50.0, n, consistent=consistent)
            b = elements_banded(s, w, 0.5, 50.0, n, consistent=consistent)
            assert all(abs(x - y) <= 1e-9 * abs(y) for x, y in zip(a, b)), (w, n, a, b)


def test_stiff_rod_top_force_is_the_rigid_inertia_at_any_element_count():
    # a stiff rod far below its axial frequency moves rigidly: the top carries (M + m L) omega^2 per unit
    # amplitude, to (omega / omega_ax)^2 = 5e-10; a force formed as a difference of the k / h terms loses
    # this at large N (the banded solve is off by 2e-4 at N = 128)
    rod = _rod(ae=1e9, length=20.0, mass=0.5, end=260.0)
    w = 0.01
    rigid = (rod.end_mass + rod.mass * rod.length) * w**2
    for n in (2, 16, 128):
        assert abs(abs(elements(rod, w, 0.0, 0.0, n, consistent=False)[2]) - rigid) < 1e-7 * rigid


def test_hanging_string_is_the_limit_of_fine_elements_with_their_own_tensions():
    # the hanging chain's Bessel (Hankel) solution against N = 1000 and 2000 lumped elements, each with the
    # tension at its mid-point, extrapolated (Richardson, second order), from light to heavy drag damping
    # (scaled Hankel functions: no overflow where the string attenuates the top motion by 1e-40)
    from cablesys.ladder.continuum import hanging_string
    s = Member(length=300.0, stiffness=complex(2e4), mass=3.0, drag=1.0, end_mass=500.0, end_drag=50.0, current=0.0,
               gradient=40.0)
    assert s.varies()
    for w, c in ((0.1, 0.01), (1.0, 1.0), (1.0, 30.0), (5.0, 0.01)):
        ref = hanging_string(s, w, c, 5.0)
        fine = [elements(s, w, c, 5.0, n, consistent=False) for n in (1000, 2000)]
        rich = [(4 * b - a) / 3 for a, b in zip(*fine)]
        assert all(abs(x - y) <= 1e-6 * abs(y) for x, y in zip(rich, ref)), (w, c)


def test_hanging_string_frequency_falls_between_its_end_tensions():
    # a string fixed at both ends (huge body) whose tension grows toward the top: its first resonance of the
    # top force lies between those of uniform strings at the bottom and top tensions
    def peak(member, ws):
        f = [abs(exact(member, w, 1e-4, 0.0)[2]) for w in ws]
        return ws[int(np.argmax(f))]
    g, length, m = 60.0, 100.0, 2.0
    s = Member(length=length, stiffness=complex(1e4), mass=m, drag=0.0, end_mass=1e12, end_drag=0.0, current=0.0,
               gradient=g)
    t_top, t_bot = s.end_stiffness()
    lo, hi = (math.pi / length * math.sqrt(t / m) for t in (t_bot, t_top))
    w1 = peak(s, np.linspace(0.9 * lo, 1.1 * hi, 4001))
    assert lo < w1 < hi


def test_drag_shares_are_the_segmented_models_quadrature():
    # the drag at p mid-points with linear velocity, shared by virtual work: one point gives (1/4, 1/4), many
    # points the exact integral of the linear shape functions (1/3, 1/6); the shares always add to 1/2
    # (the element's drag c h split between its two nodes)
    from cablesys.ladder.continuum import drag_shares
    assert drag_shares(1) == (0.25, 0.25)
    assert drag_shares(0) == (1 / 3, 1 / 6)
    d, o = drag_shares(1000)
    assert abs(d - 1 / 3) < 1e-6 and abs(o - 1 / 6) < 1e-6
    assert all(abs(sum(drag_shares(p)) - 0.5) < 1e-15 for p in (1, 2, 3, 5, 10))


def test_local_drag_string_agrees_with_the_one_damping_string_where_every_element_moves_alike():
    # far below the string's first mode with a light body the string moves as one piece: every element's
    # speed is the ends' mean, so the element-by-element linearization gives the one-damping answer
    from cablesys.ladder import local_drag
    s = Member(length=10.0, stiffness=complex(1e6), mass=0.5, drag=5.0, end_mass=1.0, end_drag=1.0, current=0.0)
    w, top = 0.5, 0.2 + 0j
    for n in (2, 5):
        one = respond(s, w, top, "segmented", n)[0]
        assert abs(local_drag.chain(s, w, top, n) - one) < 1e-6 * abs(one)


def test_local_drag_string_converges_to_its_extrapolated_limit_at_second_order():
    # a string forced near its first mode (bulging: the element-by-element drag differs from the ends' mean)
    from cablesys.ladder import local_drag
    s = Member(length=100.0, stiffness=complex(1e4), mass=2.0, drag=0.5, end_mass=500.0, end_drag=50.0, current=0.0,
               gradient=30.0)
    w1 = math.pi / 100.0 * math.sqrt(1e4 / 2.0)
    w, top = 0.8 * w1, 0.3 + 0j
    ref, _ = local_drag.reference(s, w, top)
    err = [abs(local_drag.chain(s, w, top, n) - ref) for n in (8, 16, 32)]
    rates = np.log2(np.array(err[:-1]) / np.array(err[1:]))
    assert np.all(np.abs(rates - 2.0) < 0.3), rates
