"""
A design check with its FRF
===========================

A tool on CoGiRo's platform excites it between 1.5 and 2.0 Hz. Is a platform mode in that
band (with a 5 % margin)? Are cable modes close to global modes? Are the tensions and
sags within their limits? The checks answer on one line each; the receptance shows the
forbidden band against the modes.
"""

import numpy as np

import dynstiff as ds
from dynstiff.analyses.checks import design_checks
from dynstiff.plot import plot_frf

scene = ds.load_scene("cogiro")
eq = scene.equilibrium()
checks = design_checks(scene.robot, eq.pose, band_hz=(1.5, 2.0))
print(checks.text())

# %%
# The receptances with the modes marked (red global, purple mixed, blue local) and the
# forbidden band shaded:

model = ds.scene_model(scene)                   # the scene's cable model and damping
res = ds.frf(model, 2 * np.pi * np.linspace(0.5, 6.0, 3000), inputs=["fx", "fz"],
             outputs=["x", "z"])
fig = plot_frf(res, ds.modes(model, fmax_hz=6.0))
fig.axes[0].axvspan(1.5, 2.0, color="0.8", alpha=0.5, label="forbidden band")
fig.axes[0].legend(fontsize="small")
