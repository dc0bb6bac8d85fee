"""Benchmark: CoGiRo workspace maps (goal: 10,000 poses with the first 20 modes in under
60 s of wall time on 2 cores; targets per pose: inverse statics <= 5 ms CPU, statics + 20
modes <= 12 ms CPU).

Run:  python benchmarks/bench_workspace.py [--poses N] [--no-dask]

Prints, all measured in this run:
- CPU ms per pose of inverse statics: the batched Newton on (H, V0, L0), cold and
  warm-started from the neighbouring pose, next to the per-cable Brent search it replaced
  (the same fixed point with every cable handed to the scalar solver);
- CPU ms per pose of statics + 20 modes: the workspace path (Wittrick-Williams frequencies,
  platform participation from dK/d(omega^2)) and statics + dynstiff.modes;
- poses per second of dynstiff.workspace on a grid: serial, 2 local processes and a Dask
  LocalCluster with 2 worker processes, and the projected wall time of 10,000 poses.
"""

import argparse
import time

import numpy as np

import dynstiff as ds
from dynstiff import statics
from dynstiff.workspace_map import evaluate_chunk

N_MODES = 20
BAND = (0.0, 1.5)


def cpu_per_call(fn, items):
    t = time.process_time()
    for it in items:
        fn(it)
    return 1e3 * (time.process_time() - t) / len(items)


def line_of_poses(n):
    """n feasible CoGiRo poses 5 cm apart along a diagonal of the central workspace."""
    s = np.linspace(0.0, 1.0, n)[:, None]
    P = np.array([-2.0, -1.5, 0.8]) + s * np.array([4.0, 3.0, 1.6])
    return np.hstack([P, np.zeros_like(P)])


def statics_rows(robot, poses):
    rows = {}
    rows["statics, batched Newton, cold"] = cpu_per_call(
        lambda x: robot.equilibrium(pose=x), poses)
    prev = [None]

    def warm(x):
        prev[0] = robot.equilibrium(pose=x, start=prev[0])
    rows["statics, batched Newton, warm"] = cpu_per_call(warm, poses)
    batched = statics.taut_catenaries

    def scalar_only(anchors, ends, tensions, EA, w0, start=None):
        nan = np.full(len(tensions), np.nan)
        return nan, nan.copy(), nan.copy(), nan.copy(), np.ones(len(tensions), bool)
    statics.taut_catenaries = scalar_only
    try:
        rows["statics, per-cable Brent (previous)"] = cpu_per_call(
            lambda x: robot.equilibrium(pose=x), poses[:5])
    finally:
        statics.taut_catenaries = batched
    return rows


def modes_rows(robot, poses):
    rows = {}
    t = time.process_time()
    evaluate_chunk(robot, poses, N_MODES, BAND, 0.05, 0.03, 0.02, "dsm", {})
    rows["statics + 20 modes + checks (workspace)"] = 1e3 * (time.process_time() - t) / len(
        poses)

    def full(x):
        ds.modes(ds.build_model(robot.equilibrium(pose=x), "dsm"), n_modes=N_MODES)
    rows["statics + dynstiff.modes(20)"] = cpu_per_call(full, poses[:5])
    return rows


def throughput(robot, n_poses, use_dask):
    """Wall time of a map of about n_poses positions over the frame (a k x k x k grid of
    poses, chunks of about n / 16 poses): serial, 2 local processes, Dask LocalCluster."""
    k = max(2, round(n_poses ** (1 / 3)))
    grid = np.stack(np.meshgrid(np.linspace(-5.0, 5.0, k), np.linspace(-3.5, 3.5, k),
                                np.linspace(0.5, 3.0, k), indexing="ij"), -1).reshape(-1, 3)
    kw = {"n_modes": N_MODES, "band_hz": BAND, "chunk_size": max(5, len(grid) // 16)}
    out = {}
    t, c = time.perf_counter(), time.process_time()
    m = ds.workspace(robot, grid, **kw)
    out["serial"] = (len(grid), time.perf_counter() - t, int(m["feasible"].sum()),
                     time.process_time() - c)
    t = time.perf_counter()
    ds.workspace(robot, grid, workers=2, **kw)
    out["2 local processes"] = (len(grid), time.perf_counter() - t, None, None)
    if use_dask:
        from distributed import Client, LocalCluster
        with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                          dashboard_address=None) as cluster, Client(cluster) as client:
            t = time.perf_counter()
            ds.workspace(robot, grid, client=client, **kw)
            out["Dask LocalCluster, 2 workers"] = (len(grid), time.perf_counter() - t, None,
                                                   None)
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--poses", type=int, default=300, help="grid size for the throughput")
    ap.add_argument("--no-dask", action="store_true", help="skip the Dask cluster")
    args = ap.parse_args(argv)
    robot = ds.load_scene("cogiro").robot
    poses = line_of_poses(40)
    rows = statics_rows(robot, poses)
    rows.update(modes_rows(robot, poses))
    base = rows["statics, batched Newton, cold"]
    print(f"{'CPU per CoGiRo pose':<42s} {'ms':>8s} {'ratio':>8s}")
    for name, v in rows.items():
        print(f"{name:<42s} {v:8.2f} {v / base:8.2f}")
    print()
    print(f"{'workspace map (grid, 20 modes)':<32s} {'poses':>6s} {'feasible':>8s} "
          f"{'wall s':>7s} {'poses/s':>8s} {'10k poses [s]':>14s}")
    for name, (n, dt, nf, cpu) in throughput(robot, args.poses, not args.no_dask).items():
        print(f"{name:<32s} {n:6d} {'' if nf is None else nf:>8} {dt:7.1f} {n / dt:8.1f} "
              f"{1e4 * dt / n:14.0f}")
        if cpu is not None:
            serial_cpu = cpu / n
    print(f"\nserial CPU per grid pose {1e3 * serial_cpu:.1f} ms: 10,000 poses on 2 idle cores "
          f"in about {1e4 * serial_cpu / 2:.0f} s")
    return rows


if __name__ == "__main__":
    main()
