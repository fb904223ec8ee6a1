"""The ladder's built-in rungs, one module each: what a rung builds, which scenes it can run (its validity), its
estimated error and its cost. :mod:`cablesys.ladder.rungs` holds them in ladder order with the registered ones."""
