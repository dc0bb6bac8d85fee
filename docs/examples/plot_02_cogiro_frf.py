"""
Modes and FRFs of CoGiRo
========================

The main job on the built-in CoGiRo scene (8 cables, 15 x 11 x 6 m): the statics with
sagging cables, every mode below 8 Hz (the Wittrick-Williams count misses none), labelled
global or local by the platform's share of its kinetic energy, and the receptances
fz -> z and fx -> x with the modes marked.
"""

import numpy as np

import dynstiff as ds
from dynstiff.plot import plot_frf

scene = ds.load_scene("cogiro")
eq = scene.equilibrium()                        # inverse statics at the scene's pose
print(eq.to_frame().round(4))

model = ds.scene_model(scene)                   # closed form, the scene's [damping]
modes = ds.modes(model, fmax_hz=8.0)
print(modes.to_frame()[["mode", "freq [Hz]", "kind", "platform share [-]"]].head(12))

# %%
# The receptances, on a grid refined at every mode; red lines are global modes, blue local
# (cable) modes:

res = ds.frf(model, 2 * np.pi * np.linspace(0.5, 8.0, 4000), inputs=["fz", "fx"],
             outputs=["z", "x"])
fig = plot_frf(res, modes)
