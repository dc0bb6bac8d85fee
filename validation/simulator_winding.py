"""Eight-cable motion simulator with heavy cables wound on drums (seed paper 001; scene
``simulator``): the energy balance while cable mass moves onto and off the drums, and the
eigenfrequencies along the motion.

The paper builds a port-Hamiltonian model whose cables change mass, stiffness and length
as they are wound (total cable mass / platform mass = 3/4) and whose motors carry drums of
kinetic energy 1/2 m_d r_d^2 theta'^2; it gives no numbers. Here the platform moves 5 m along
x at 1 m/s (1 s speed ramps); the winches follow the quasi-static cable lengths
(:func:`dynstiff.timedomain.trajectory.track`), which winds about 2.8 m onto four drums and pays as
much off the other four (a quarter of the cable mass changes hands). The balance of the
lumped-mass model (4 segments per cable; see :mod:`dynstiff.timedomain.simulation`)::

    E(t) - E(0) = W_winch + E_carried - D + residual

(E kinetic + gravity + elastic energy of platform and cables, W_winch the work of the winches
on the cables, E_carried the kinetic energy the paid-out mass brings). The drums, driven
kinematically (theta' = L0' / r_d), store 1/2 m_d L0'^2 each, so the motors supply
W_motor = W_winch + E_drums(t) - E_drums(0). The residual, relative to the energy scale of
the run, is the headline. It measures the trapezoidal quadrature of the winch work, which
is accurate only once dt resolves the axial chain modes (period about 1.4 ms here, EA = 1e7 N
on 1.5 m segments of 1.4 kg): on the whole 5 m path 0.64 at dt = 1 ms, 2.9e-4 at 0.5 ms
(on the first metre, ``quick``: 0.029 and 1.3e-4); the motion itself is the same at both.

Eigenfrequencies along the motion: the closed-form model at poses along the path, every
mode below 24 Hz (the heavy cables put about 60 local modes below the first global one,
near 10 Hz), global modes tracked (:func:`dynstiff.sweep`), and the lumped model at the
path's end as a check.

Run ``python validation/simulator_winding.py`` for the tables and ``simulator_winding.png``.
"""

import numpy as np
import pandas as pd

import dynstiff as ds
from dynstiff.timedomain.trajectory import line, track


def winding_run(dt=5e-4, segments=4, quick=False):
    """Simulate the winding motion.

    Returns
    -------
    row : dict
        Energy-balance summary.
    frame : pandas.DataFrame
        Energy terms against time [J].
    """
    scene = ds.load_scene("simulator")
    st = scene.study
    end = np.array(st["path_end"], dtype=float)
    start = np.array(st["path_start"], dtype=float)
    if quick:
        end = start + np.array([1.0, 0.0, 0.0])
    traj = line(start, end, st["speed"], ramp=st["ramp"])
    res = track(scene.robot, traj, segments=segments, dt=dt, settle=0.5)
    r = res.response
    e = r.energy
    rate = np.gradient(r.unstretched_lengths, r.times, axis=0)           # L0' [m/s]
    drums = 0.5 * st["drum_mass"] * np.sum(rate ** 2, axis=1)             # [J]
    motor = e.winch_work + drums - drums[0]
    mu = np.array([c.mass_per_length for c in scene.robot.cables])
    moved = np.abs(r.unstretched_lengths[-1] - r.unstretched_lengths[0])
    row = {
        "dt [s]": dt, "segments": segments,
        "path [m]": float(np.linalg.norm(end - start)),
        "largest length change [m]": float(moved.max()),
        "cable mass moved [kg]": float(np.sum(mu * moved)),
        # the scene's definition: at the central pose (at the path's start, 2.5 m off
        # centre, the cables are 2.4 m longer in all)
        "cable mass / platform mass [-]": float(
            np.sum(mu * scene.equilibrium().unstretched_lengths) / scene.robot.platform.mass),
        "same, path start [-]": float(np.sum(mu * r.unstretched_lengths[0])
                                      / scene.robot.platform.mass),
        "winch work [J]": float(e.winch_work[-1]),
        "peak drum kinetic energy [J]": float(drums.max()),
        "peak motor work [J]": float(np.abs(motor).max()),
        "energy scale [J]": e.scale,
        "max |residual| / scale [-]": float(np.abs(e.relative_residual).max()),
        "max deviation from path [m]": res.max_deviation,
        "wall time [s]": r.wall_time,
    }
    frame = pd.DataFrame({"time [s]": r.times, "kinetic [J]": e.kinetic,
                          "gravity [J]": e.gravity, "elastic [J]": e.elastic,
                          "winch work [J]": e.winch_work, "carried [J]": e.carried_kinetic,
                          "drums [J]": drums, "motor work [J]": motor,
                          "residual [J]": e.residual})
    return row, frame


def frequencies_along(steps=6, fmax_hz=24.0, n_check=20):
    """Modes along the path (closed form) and a lumped-model check at its end.

    With cables of 3/4 the platform's mass no mode below 24 Hz keeps most of its kinetic
    energy in the platform (the platform's share is at most 40 % along the path): the
    "global" modes have dissolved into the cable modes. The modes with the largest platform
    share are listed at each step instead.

    Returns
    -------
    table : pandas.DataFrame
        One row per step and mode among the 6 with the largest platform share: arc
        length [m], frequency [Hz], platform energy share [-].
    check : dict
        The lowest ``n_check`` frequencies at the end pose against the lumped model with
        N = 16 and 32 segments per cable: largest relative differences [-].
    """
    scene = ds.load_scene("simulator")
    st = scene.study
    poses = np.linspace(st["path_start"], st["path_end"], steps)
    sw = ds.sweep(scene.robot, poses=poses, fmax_hz=fmax_hz)
    rows = []
    for k, modes in enumerate(sw.modal):
        # the sweep computes modes above fmax_hz until it holds the platform modes
        # (theory.md §12.4): the study is about the modes below fmax_hz
        share = np.where(modes.freq_hz <= fmax_hz, 1.0 - modes.cable_energy_fraction, -1.0)
        for j in np.argsort(share)[::-1][:6]:
            rows.append({"arc length [m]": sw.values[k], "freq [Hz]": modes.freq_hz[j],
                         "platform energy share [-]": share[j]})
    eq = sw.equilibria[-1]
    f = sw.modal[-1].freq_hz[:n_check]
    check = {"largest platform share [-]": float(max(r["platform energy share [-]"]
                                                   for r in rows))}
    for N in (16, 32):
        lm = ds.build_model(eq, "lumped", segments=N)
        check[f"lumped N={N}, max relative difference [-]"] = float(
            np.max(np.abs(ds.eigenfrequencies(lm, n_check) / f - 1)))
    return pd.DataFrame(rows), check


def run(quick=False):
    """Energy balance at two time steps, and the frequencies along the motion.

    Returns
    -------
    energy : pandas.DataFrame
        One row per time step (see :func:`winding_run`).
    modes : pandas.DataFrame
        Modes with the largest platform share along the path (:func:`frequencies_along`).
    check : dict
        Lumped-model check at the end pose (:func:`frequencies_along`).
    """
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ds.lumped.EnergyBalanceWarning)
        rows = [winding_run(dt, quick=quick)[0]
                for dt in ((5e-4,) if quick else (1e-3, 5e-4))]
    table, check = frequencies_along(steps=3 if quick else 6)
    return pd.DataFrame(rows), table, check


if __name__ == "__main__":
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    pd.set_option("display.width", 200)
    energy, modes, check = run()
    print(energy.T.to_string())
    print(modes.to_string(index=False, float_format=lambda x: f"{x:.4g}"))
    print(check)
    _, frame = winding_run(5e-4)
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    t = frame["time [s]"]
    for col in ("kinetic [J]", "winch work [J]", "drums [J]", "motor work [J]",
                "residual [J]"):
        axes[0].plot(t, frame[col], label=col)
    e = frame["kinetic [J]"] + frame["gravity [J]"] + frame["elastic [J]"]
    axes[0].plot(t, e - e.iloc[0], "k--", label="E(t) - E(0) [J]")
    axes[0].set_xlabel("time [s]")
    axes[0].set_ylabel("energy [J]")
    axes[0].legend(fontsize=8)
    sc = axes[1].scatter(modes["arc length [m]"], modes["freq [Hz]"],
                         c=modes["platform energy share [-]"], cmap="viridis")
    fig.colorbar(sc, ax=axes[1], label="platform energy share [-]")
    axes[1].set_xlabel("arc length [m]")
    axes[1].set_ylabel("frequency [Hz]")
    fig.tight_layout()
    fig.savefig("simulator_winding.png", dpi=120)
