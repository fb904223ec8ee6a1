"""The signals every cable model shares: its exogenous input e and its outputs per section.

``EXO_LABELS`` names the entries of e = (t, x_s, y_s, x_s', y_s', x_s'', y_s''): time (s), the
top position (m, x right, y down), its velocity (m/s) and acceleration (m/s^2), in the order
:func:`.top_motion.top_motion_function` returns them and the models' ``dynamics``/``outputs``
take them. ``OUTPUT_NAMES`` names a section's outputs, in the order both the 2-DOF chain
(:mod:`.build`) and the segmented cable (:mod:`.segmented`) give them: angle phi (rad) of the
section (for the segmented cable, of its chord) and its stretch u (m) beyond its zero-tension length
(Wang 1971 eq. 1; for the segmented cable the sum of the element elongations) with their rates, the
body's position x_b, y_b (m, y from the mean top depth) and velocity, the spring force F_bc
(N, Wang 1971 eq. 54) and the cable's pull on its body and on its top point (N).
``CHORD_NAMES`` are the segmented cable's extra outputs per section: the chord (top point to body)
minus the zero-tension length (m, negative when the cable sags) and its rate (m/s).
"""

EXO_LABELS = ("t", "x_s", "y_s", "x_s_rate", "y_s_rate", "x_s_acc", "y_s_acc")
OUTPUT_NAMES = ("phi", "phi_rate", "u", "u_rate", "x_b", "x_b_rate", "y_b", "y_b_rate", "tension",
                "tension_bottom", "tension_top")
CHORD_NAMES = ("chord_stretch", "chord_stretch_rate")
