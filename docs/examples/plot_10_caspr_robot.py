"""
A robot imported from CASPR
===========================

CASPR, the MATLAB cable-robot toolbox, describes a robot in two XML files (bodies and
cables). ``Robot.from_caspr`` reads a single-body model; CASPR holds no cable mass or axial
stiffness, so the cable is given here. The robot is IPAnema 1 (Fraunhofer IPA, eight
cables); its statics at the model's initial pose, the cable model it needs, its modes and
its first global mode. ``dynstiff import-caspr`` writes the same robot as a scene file.
"""

from pathlib import Path

import dynstiff as ds
from dynstiff.io.caspr import read_caspr
from dynstiff.report.robot3d import plot_robot

try:
    here = Path(__file__).resolve().parent
except NameError:                                  # run interactively
    here = Path.cwd()
data = here.parents[1] / "tests" / "data" / "caspr"   # CASPR's files, in the repository
bodies, cables = data / "IPAnema_1_bodies.xml", data / "IPAnema_1_cables.xml"

cable = ds.Cable(mass_per_length=0.02, EA=1.0e5)   # a light synthetic line [kg/m], [N]
# CASPR's least cable force is 0 N, a slack sagging cable: hold every cable at 50 N or more
robot = ds.Robot.from_caspr(bodies, cables, cable=cable, min_tension=50.0)
initial = read_caspr(bodies, cables)
eq = robot.equilibrium(pose=[*initial.position, *initial.rotation])
print(robot.name)
print(eq.to_frame().round(4))

rec = ds.recommend_model(eq, band_hz=(0.1, 10.0), rtol=1e-2)
print(rec.text())
model = ds.build_model(eq, rec.rung, **({"fmax_hz": 10.5} if rec.rung == "exact" else {}))
modes = ds.modes(model, n_modes=12)
print(modes.to_frame()[["mode", "freq [Hz]", "kind", "platform share [-]"]])

# %%
# The first global mode, its cables drawn with their own displacement fields:
k = next(j for j, kind in enumerate(modes.kind) if kind == "global")
fig = plot_robot(eq, modes, k, model=model)
