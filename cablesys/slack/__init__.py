"""Slack cables: Irvine–Caughey theory and a converged lumped-mass solver.

Griffin & Rosenthal (1985), "The Dynamics of Slack Marine Cables", NRL MR 5559.
"""
