"""One cable, which knows no robot: the elastic catenary (one and many at once), the
chord-frame parameters of the linear theory, the closed-form dynamic stiffness, its modes
and its guard, the exact cable about the true catenary, lumped-mass chains and the mpmath
reference."""
