"""The signals every cable model shares: its exogenous input e and its outputs per section.

``EXO_LABELS`` names the entries of e = (t, x_s, y_s, x_s', y_s', x_s'', y_s''): time (s), the
top position (m, x right, y down), its velocity (m/s) and acceleration (m/s^2), in the order
:func:`.top_motion.top_motion_function` returns them and the models' ``dynamics``/``outputs``
take them. ``OUTPUT_NAMES`` names a section's outputs, in the order every model that has sections
gives them (the 2-DOF chain :mod:`.build`, the segmented cable :mod:`.segmented`, the quasi-static
reductions :mod:`.quasistatic`), each with one meaning in all of them:

- ``phi`` (rad): the angle of the chord, the straight line from the section's top end to its body,
  from the vertical (e_t = (-sin phi, cos phi), Wang 1971 eq. 10). Wang's cable is straight, so its
  angle coordinate is that chord's angle; for the segmented cable it is computed from the end nodes.
  ``phi_rate`` its rate (rad/s);
- ``u`` (m): the stretch of the section's cable beyond its zero-tension length (Wang 1971 eq. 1;
  for the segmented cable the sum of the element elongations), ``u_rate`` its rate (m/s);
- ``x_b``, ``y_b`` (m, y down from the mean top depth) the body's position and velocity;
- ``tension_mid`` (N): the cable tension at mid-length (unstretched arc length l_0 / 2) of the
  section. Wang's cable has one uniform stretch, so its tension is the spring force
  F_bc = k u + (C_I / l_r) u' with the slack floor (Wang 1971 eq. 46, 54); hanging at rest the
  uniform stretch makes it the mean tension W_b + W_c / 2, which is the tension at mid-length. The
  segmented cable interpolates its element tensions linearly in unstretched arc length between the
  mid-points of the two elements around s = l_0 / 2 (:mod:`.segmented`);
- ``tension_bottom`` (N): the cable's pull on its body (the tension at the body end);
- ``tension_top`` (N): the cable's pull on its top point (the tension at the top end).

No output is called bare ``tension``: a tension is always named by where along the cable it is.
The segmented cable's tension per element is its profile ``element_tension[k]`` (k = 0.. top to
bottom; in a chain a suffix names the section, ``tension_mid_2`` the second section's, not an element).
``CHORD_NAMES`` are the segmented cable's extra outputs per section: the chord (top point to body)
minus the zero-tension length (m, negative when the cable sags) and its rate (m/s).
"""

EXO_LABELS = ("t", "x_s", "y_s", "x_s_rate", "y_s_rate", "x_s_acc", "y_s_acc")
OUTPUT_NAMES = ("phi", "phi_rate", "u", "u_rate", "x_b", "x_b_rate", "y_b", "y_b_rate", "tension_mid",
                "tension_bottom", "tension_top")
CHORD_NAMES = ("chord_stretch", "chord_stretch_rate")
