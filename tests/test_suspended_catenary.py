"""The inextensible catenary between two points (cablesys.statics.closed_forms.suspended_catenary, Irvine 1981 ch. 1),
the statics' first guess for a line hanging free between its ends: it passes through both ends, its arc length is
the line's, and its slope obeys the catenary's dY/dX = sinh((X - X0) / a), from taut to a line many times its chord."""

import numpy as np
import pytest

from cablesys.statics.closed_forms import suspended_catenary


@pytest.mark.parametrize("ratio", [1.01, 1.5, 3.0, 10.0, 40.0])
@pytest.mark.parametrize("anchor", [(30.0, 5.0), (-30.0, -20.0), (8.0, 60.0)])
def test_the_catenary_joins_its_ends_with_its_own_length(ratio, anchor):
    """Length = ratio x chord (a near-vertical slack line has 2 a sinh(h / 2a) / h far above 2.5, where the root's
    old bracket 1 + asinh(target) held no sign change)."""
    length = ratio * float(np.hypot(*anchor))
    err = []
    for n in (8000, 16000):
        pts = suspended_catenary(length, anchor, np.linspace(0.0, length, n + 1))
        np.testing.assert_allclose(pts[0], [0.0, 0.0], atol=1e-9 * length)
        np.testing.assert_allclose(pts[-1], anchor, atol=1e-7 * length)
        err.append(length - float(np.sum(np.hypot(*np.diff(pts, axis=0).T))))   # chords fall short of the arc
    assert 0.0 < err[1] < 1e-4 * length
    assert err[0] / err[1] == pytest.approx(4.0, rel=0.05)               # the chords' O(h^2): parametrised by arc
