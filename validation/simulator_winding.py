"""Eight-cable motion simulator with heavy cables wound on drums (seed paper 001; scene
``simulator``): the energy balance while cable mass moves onto and off the drums, and the
eigenfrequencies along the motion.

The paper builds a port-Hamiltonian model whose cables change mass, stiffness and length
as they are wound (total cable mass / platform mass = 3/4) and whose motors carry drums of
kinetic energy 1/2 m_d r_d^2 theta'^2; it gives no numbers. Here the platform moves 5 m along
x at 1 m/s (1 s speed ramps); the winches follow the quasi-static cable lengths
(:func:`dynstiff.trajectory.track`), which winds about 2.8 m onto four drums and pays as much
off the other four (a quarter of the cable mass changes hands). The balance of the
lumped-mass model (4 segments per cable; see :mod:`dynstiff.lumped.time_domain`)::

    E(t) - E(0) = W_winch + E_carried - D + residual

(E kinetic + gravity + elastic energy of platform and cables, W_winch the work of the winches
on the cables, E_carried the kinetic energy the paid-out mass brings). The drums, driven
kinematically (theta' = L0' / r_d), store 1/2 m_d L0'^2 each, so the motors supply
W_motor = W_winch + E_drums(t) - E_drums(0). The residual, relative to the energy scale of
the run, is the headline. It measures the trapezoidal quadrature of the winch work, which
is accurate only once dt resolves the axial chain modes (period about 1.4 ms here, EA = 1e7 N
on 1.5 m segments of 1.4 kg): 0.12 at dt = 1 ms, 1.6e-4 at 0.5 ms on the first 1.5 m of the
path; the motion itself is the same at both.

Eigenfrequencies along the motion: the closed-form model at poses along the path, global
modes tracked (:func:`dynstiff.sweep`), and the lumped model at the path's end as a check.

Run ``python validation/simulator_winding.py`` for the tables and ``simulator_winding.png``.
"""

import numpy as np
import pandas as pd

import dynstiff as ds
from dynstiff.trajectory import line, track


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
        "cable mass / platform mass [-]": float(np.sum(mu * r.unstretched_lengths[0])
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


def frequencies_along(steps=6, n_modes=30):
    """Modes along the path (closed form) and a lumped-model check at its end.

    Returns
    -------
    sweep : SweepResult
    check : dict
        Lowest global frequencies at the end pose: closed form and lumped (N = 16) [Hz],
        their largest relative difference.
    """
    scene = ds.load_scene("simulator")
    st = scene.study
    poses = np.linspace(st["path_start"], st["path_end"], steps)
    sw = ds.sweep(scene.robot, poses=poses, n_modes=n_modes)
    eq = sw.equilibria[-1]
    modes = sw.modal[-1]
    lm = ds.LumpedMassModel(scene.robot, eq.unstretched_lengths, 16)
    lm.equilibrium(initial_pose=eq.pose)
    f_lm = lm.eigenfrequencies(n_modes)
    glob = np.array(modes.kind) == "global"
    f_g = modes.freq_hz[glob]
    near = f_lm[np.argmin(np.abs(f_lm[None, :] - f_g[:, None]), axis=1)]
    return sw, {"global, closed form [Hz]": np.round(f_g, 4).tolist(),
                "global, lumped N=16 [Hz]": np.round(near, 4).tolist(),
                "max relative difference [-]": float(np.max(np.abs(near / f_g - 1)))
                if f_g.size else np.nan,
                "all first modes, max relative difference [-]":
                    float(np.max(np.abs(f_lm / modes.freq_hz - 1)))}


def run(quick=False):
    """Energy balance at two time steps, and the frequencies along the motion.

    Returns
    -------
    energy : pandas.DataFrame
        One row per time step (see :func:`winding_run`).
    modes : pandas.DataFrame
        Veering table (global tracks [Hz] per step) with the abscissa [m].
    check : dict
        Lumped-model check at the end pose (:func:`frequencies_along`).
    """
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ds.lumped.EnergyBalanceWarning)
        rows = [winding_run(dt, quick=quick)[0]
                for dt in ((5e-4,) if quick else (1e-3, 5e-4))]
    sw, check = frequencies_along(steps=3 if quick else 6, n_modes=20 if quick else 30)
    vt = sw.veering_table()
    vt.insert(0, sw.parameter, sw.values)
    return pd.DataFrame(rows), vt, check


if __name__ == "__main__":
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from dynstiff.plot import plot_veering

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
    sw, _ = frequencies_along()
    plot_veering(sw, ax=axes[1])
    fig.tight_layout()
    fig.savefig("simulator_winding.png", dpi=120)
