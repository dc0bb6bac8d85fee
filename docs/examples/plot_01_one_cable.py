"""
One sagging cable
=================

One of CoGiRo's 4 mm steel cables (0.064 kg/m, E = 17 GPa), pulled to 300 N at the
platform: the exact elastic catenary between anchor A and attachment B, then the dynamic
stiffness of the end B in the cable's chord frame. The transverse stiffness starts at the
static value T/L, drops through zero and flips sign at the cable's own clamped
frequencies: near them the cable, not the platform, moves (theory.md §2-§3).
"""

import matplotlib.pyplot as plt
import numpy as np

import dynstiff as ds

cable = ds.Cable(mass_per_length=0.064, EA=8.2051e-6 * 17e9)    # [kg/m], [N]
A, B = [-7.1775, -5.4361, 5.3911], [0.5032, -0.4928, 1.0]        # [m], z up
state = ds.unstretched_length_for_tension(A, B, 300.0, cable)    # 300 N at B
print(f"L0 = {state.unstretched_length:.4f} m, sag = {state.sag * 1e3:.1f} mm, "
      f"lambda^2 = {state.lambda_sq:.3f}")
modes = ds.cable_natural_frequencies(state, 6)
print(modes.to_frame())

# %%
# The end stiffness over 0-12 Hz, rotated into the chord frame (u along the chord, v in
# the cable's plane, w out of it):

freq = np.linspace(0.0, 12.0, 4000)
K = ds.cable_dynamic_stiffness(state, 2 * np.pi * freq)          # (4000, 3, 3) [N/m]
R = ds.chord_parameters(state).rotation
K_chord = R.T @ K @ R

fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(10, 4), width_ratios=[1, 2],
                               layout="constrained")
d = state.profile(80) - np.asarray(A)                          # points from A [m]
u = R[:, 0]                                                      # chord direction A -> B
along = d @ u
below = np.linalg.norm(d - np.outer(along, u), axis=1)           # distance from the chord
ax0.plot(along, 1e3 * below)
ax0.set(xlabel="along the chord from A [m]", ylabel="distance from the chord [mm]",
        title=f"sag of the catenary, chord {state.chord_length:.2f} m")
for i, name in enumerate(["K_uu (chord)", "K_vv (in-plane)", "K_ww (out-of-plane)"]):
    ax1.semilogy(freq, np.abs(K_chord[:, i, i]), lw=1.0, label=name)
for f in modes.freq_hz[modes.freq_hz < 12]:
    ax1.axvline(f, color="0.6", lw=0.6, ls=":")
ax1.set(xlabel="frequency [Hz]", ylabel="|K| [N/m]",
        title="end-B dynamic stiffness (dotted: clamped modes)")
ax1.legend(loc="lower left")
plt.show()
