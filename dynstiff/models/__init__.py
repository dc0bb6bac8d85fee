"""The model ladder behind one interface (:class:`dynstiff.models.base.PlatformModel`):
massless springs and catenaries, the closed-form dynamic stiffness ("dsm"), the exact
cable about its true catenary ("exact"), and lumped-mass chains (nonlinear, and
linearised: "lumped"); :func:`dynstiff.models.ladder.build_model` builds any rung."""
