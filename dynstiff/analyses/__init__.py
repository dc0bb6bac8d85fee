"""Analyses, plain functions of any model: FRFs, eigenfrequencies (Wittrick-Williams) and
modes, damped roots, platform participation, modal interaction and sweeps, model choice,
design checks and the analysis settings of a scene, reduced modal models, measured data
and calibration."""
