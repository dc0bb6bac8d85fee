"""
A global mode and its cables
============================

Each heavy cable has modes of its own (local modes); the platform on its cables has six
global ones. Where a local mode comes close to a global one they share energy. Here:
the local modes within 3 % of a global mode, and the global mode with the largest cable
share of its kinetic energy, drawn with the cables' own displacement fields
(displacements exaggerated).
"""

import dynstiff as ds
from dynstiff.analyses.interaction import to_frame
from dynstiff.report.robot3d import plot_robot

scene = ds.load_scene("cogiro")
eq = scene.equilibrium()
model = ds.FrequencyModel(eq)
modes = ds.modes(model, fmax_hz=8.0)
print(to_frame(ds.proximity_warnings(modes, rtol=0.03)))

# %%
# The global mode that carries the most cable energy, its cables drawn with their own
# displacement fields (the closed-form fields of the model):

glob = [k for k, kind in enumerate(modes.kind) if kind == "global"]
k = max(glob, key=lambda j: modes.cable_energy_fraction[j])
print(f"mode {k + 1}: {modes.freq_hz[k]:.3f} Hz, "
      f"cable energy fraction {modes.cable_energy_fraction[k]:.3f}")
fig = plot_robot(eq, modes, k, model=model)
