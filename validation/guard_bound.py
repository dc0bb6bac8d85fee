"""Does the closed form's robot-level error estimate bound its measured error on heavy-cable
robots (docs/theory.md §11.5)?

Random suspended robots (six cables from anchors on a circle to a platform below, random
span 3-600 m, sag, tilt of the anchor plane, platform mass and inertia, EA; the cables'
total mass 1 % to 200 % of the platform's, log-uniform), each at a random pose near the
centre. For each: the measured error of the closed form, the largest relative difference
of its frequencies from the exact rung's over the first ``n_modes`` coupled modes (paired in
order), against its estimate without the exact rung,
:func:`dynstiff.analyses.recommend.estimated_error` over the same band. The headline is the
largest measured / estimated ratio (at most 1: the estimate bounds the error).
"""

import warnings

import numpy as np

import dynstiff as ds
from dynstiff.analyses.recommend import estimated_error
from dynstiff.errors import ClosedFormWarning


def random_robot(rng, mass_ratio):
    """A random six-cable suspended robot whose cables weigh ``mass_ratio`` times the
    platform [-], and a random pose near its centre. Returns (Robot, Pose)."""
    span = 10 ** rng.uniform(0.5, 2.8)                      # anchor radius [m]
    az = np.deg2rad(30 + 60 * np.arange(6) + rng.uniform(-8, 8, 6))
    height = span * rng.uniform(0.3, 1.2)                   # anchors above the platform [m]
    anchors = np.column_stack([span * np.cos(az), span * np.sin(az),
                               height + span * rng.uniform(-0.05, 0.05, 6)])
    rb = span * rng.uniform(0.01, 0.05)                     # attachment ring radius [m]
    off = np.deg2rad(rng.uniform(25, 50))
    mid = np.deg2rad(60 + 120 * (np.arange(6) // 2))
    side = np.where(np.arange(6) % 2 == 0, 1.0, -1.0)      # crossed pairs (as the fast scene)
    bz = rb * rng.uniform(0.0, 0.5)
    attachments = np.column_stack([rb * np.cos(mid + side * off),
                                   rb * np.sin(mid + side * off), np.full(6, bz)])
    mass = 10 ** rng.uniform(0.5, 4.5)                      # platform [kg]
    r_g = rb * rng.uniform(0.5, 1.2)
    inertia = mass * r_g**2 * np.diag([0.5, 0.5, rng.uniform(0.6, 1.0)])
    lengths = np.linalg.norm(anchors - attachments, axis=1)
    mu = mass_ratio * mass / lengths.sum()                  # [kg/m]
    strain = 10 ** rng.uniform(-4, -2.5)                    # static strain at m g / 6 [-]
    EA = mass * ds.constants.STANDARD_GRAVITY * (1 + mass_ratio) / 6 / strain
    cable = ds.Cable(mass_per_length=float(mu), EA=float(EA))
    robot = ds.Robot(anchors, attachments, (cable,) * 6,
                     ds.Platform(mass=float(mass), inertia=inertia))
    pos = np.array([*(span * rng.uniform(-0.1, 0.1, 2)), 0.0])
    return robot, ds.Pose(position=pos)


def measure(robot, pose, n_modes=6):
    """(measured error, estimated error, band top [Hz], cause) of the closed form on one
    robot: its first n_modes coupled frequencies against the exact rung's."""
    eq = robot.equilibrium(pose=pose)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ClosedFormWarning)    # the estimate is the subject
        dsm = ds.FrequencyModel(eq)
        f_d = ds.eigenfrequencies(dsm, n_modes=n_modes)
        exact = ds.build_model(eq, "exact", fmax_hz=1.3 * float(f_d[-1]))
        f_x = ds.eigenfrequencies(exact, n_modes=n_modes)
        hi = float(f_x[-1])
        est, cause = estimated_error(dsm, (0.0, hi))
    return float(np.max(np.abs(f_d / f_x - 1))), float(est), hi, cause


def run(n_robots=200, seed=0, n_modes=6):
    """DataFrame, one row per robot: "mass ratio [-]" (cables / platform), "span [m]",
    "band top [Hz]", "measured [-]", "estimated [-]", "ratio [-]" (measured / estimated),
    "cause"; robots with no feasible equilibrium are redrawn."""
    import pandas as pd
    rng = np.random.default_rng(seed)
    rows = []
    while len(rows) < n_robots:
        ratio = 10 ** rng.uniform(-2, np.log10(2.0))
        robot, pose = random_robot(rng, ratio)
        try:
            meas, est, hi, cause = measure(robot, pose, n_modes)
        except (ds.errors.InfeasiblePoseError, ds.errors.ConvergenceError):
            continue
        rows.append((ratio, float(np.linalg.norm(robot.anchors[0, :2])), hi, meas, est,
                     meas / est if est > 0 else np.inf, cause))
    return pd.DataFrame(rows, columns=["mass ratio [-]", "span [m]", "band top [Hz]",
                                       "measured [-]", "estimated [-]", "ratio [-]", "cause"])


if __name__ == "__main__":
    import matplotlib.pyplot as plt
    df = run()
    print(df.describe().to_string(float_format=lambda x: f"{x:.3g}"))
    print(f"largest measured / estimated: {df['ratio [-]'].max():.3g}")
    fig, ax = plt.subplots(figsize=(6, 4.5))
    sc = ax.scatter(df["estimated [-]"], df["measured [-]"], c=np.log10(df["mass ratio [-]"]),
                    s=12, cmap="viridis")
    lim = [min(df["measured [-]"].min(), df["estimated [-]"].min()) / 2, 1.0]
    ax.plot(lim, lim, "k--", lw=0.8, label="measured = estimated")
    ax.axhline(1e-2, color="0.6", lw=0.8, ls=":")
    ax.axvline(1e-2, color="0.6", lw=0.8, ls=":", label="guard_rtol 1e-2")
    ax.set(xscale="log", yscale="log", xlabel="estimated error [-]",
           ylabel="measured error, closed form vs exact [-]",
           title=f"{len(df)} random robots, first coupled modes")
    fig.colorbar(sc, label="log10(cable mass / platform mass)")
    ax.legend(loc="upper left")
    fig.tight_layout()
    fig.savefig("guard_bound.png", dpi=120)
