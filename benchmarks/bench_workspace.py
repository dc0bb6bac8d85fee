"""Benchmark: CoGiRo workspace maps (goal: 10,000 poses with the first 20 modes in under
60 s of wall time on 2 cores; targets per pose: inverse statics <= 5 ms CPU, statics + 20
modes <= 12 ms CPU).

Run:  OPENBLAS_NUM_THREADS=1 python benchmarks/bench_workspace.py [--poses N] [--repeats R]
      [--no-dask]

Prints, all measured in this run (CPU rows: the least of ``--repeats`` runs; the 1-minute
load average of the machine next to each figure, since the machine may be shared):
- CPU ms per pose of inverse statics along a line of poses, cold and warm-started from the
  neighbouring pose, and on the grid of the map (warm along its chunks); the per-cable Brent
  search of the first version (5 poses) and the numpy Newton with LP-started tension
  distributions (the path before the compiled Newton and the warm active set, theory.md
  §13.6) in the same run;
- CPU ms per pose of statics + 20 modes + checks on the map's grid (``evaluate_chunk``, the
  map's own loop), next to the same with the numpy Newton and LP-started distributions, and
  statics + ``dynstiff.modes``;
- the wall time of ``dynstiff.workspace`` on the grid serially, on 2 local processes and on
  a Dask LocalCluster with 2 worker processes, with the CPU time of parent and workers
  (``resource.getrusage``): the pool's overhead is what the parallel runs spend beyond the
  serial CPU time, its efficiency serial CPU / (2 x wall);
- the projected wall time of 10,000 poses on 2 idle cores: (serial CPU + the 2-process
  pool's overhead) per pose x 10,000 / 2.
"""

import argparse
import os
import resource
import time
from contextlib import contextmanager

import numpy as np

import dynstiff as ds
from dynstiff.maps.workspace import evaluate_chunk
from dynstiff.robot import statics

N_MODES = 20
BAND = (0.0, 1.5)


def load():
    """1-minute load average of the machine."""
    return os.getloadavg()[0]


def least_cpu(fn, repeats):
    """Least CPU time [s] of ``repeats`` calls of fn() and the load average during it."""
    best, loads = np.inf, []
    for _ in range(repeats):
        t = time.process_time()
        fn()
        best = min(best, time.process_time() - t)
        loads.append(load())
    return best, float(np.mean(loads))


def line_of_poses(n):
    """n feasible CoGiRo poses along a diagonal of the central workspace."""
    s = np.linspace(0.0, 1.0, n)[:, None]
    P = np.array([-2.0, -1.5, 0.8]) + s * np.array([4.0, 3.0, 1.6])
    return np.hstack([P, np.zeros_like(P)])


def grid_of_poses(n_poses):
    """A k x k x k grid of about n_poses positions over the frame, k = round(n^(1/3))."""
    k = max(2, round(n_poses ** (1 / 3)))
    return np.stack(np.meshgrid(np.linspace(-5.0, 5.0, k), np.linspace(-3.5, 3.5, k),
                                np.linspace(0.5, 3.0, k), indexing="ij"), -1).reshape(-1, 3)


@contextmanager
def previous_statics():
    """Inverse statics as before theory.md §13.6: the numpy Newton, and every tension
    distribution that leaves the limits started from the LP's feasible point."""
    batched, dist = statics.taut_catenaries, statics._distribution

    def numpy_newton(*args, **kw):
        return batched(*args, **{**kw, "compiled": False})

    def lp_started(W, w, t_min, t_max, t_ref=None, sides=None):
        return dist(W, w, t_min, t_max, t_ref, warm=False)
    statics.taut_catenaries, statics._distribution = numpy_newton, lp_started
    try:
        yield
    finally:
        statics.taut_catenaries, statics._distribution = batched, dist


@contextmanager
def brent_statics():
    """Inverse statics with every cable handed to the scalar bracketing solver."""
    batched = statics.taut_catenaries

    def scalar_only(anchors, ends, tensions, EA, w0, start=None):
        nan = np.full(len(tensions), np.nan)
        return nan, nan.copy(), nan.copy(), nan.copy(), np.ones(len(tensions), bool)
    statics.taut_catenaries = scalar_only
    try:
        yield
    finally:
        statics.taut_catenaries = batched


def chunked_statics(robot, X, chunk):
    """Inverse statics of every pose, warm-started along chunks as a map does."""
    for s in range(0, len(X), chunk):
        prev = None
        for x in X[s:s + chunk]:
            try:
                prev = robot.equilibrium(pose=x, start=prev)
            except ds.DynstiffError:
                try:
                    prev = robot.equilibrium(pose=x)
                except ds.DynstiffError:
                    pass


def map_chunks(robot, X, chunk):
    for s in range(0, len(X), chunk):
        evaluate_chunk(robot, X[s:s + chunk], N_MODES, BAND, 0.05, 0.03, 0.02, "dsm", {})


def cpu_rows(robot, grid, chunk, repeats):
    """(name, CPU ms per pose, load) rows."""
    line = line_of_poses(40)
    X = np.hstack([grid, np.zeros_like(grid)])
    robot.equilibrium(pose=line[0])                 # compiled kernels loaded before timing
    rows = []

    def add(name, fn, n, reps=repeats):
        cpu, ld = least_cpu(fn, reps)
        rows.append((name, 1e3 * cpu / n, ld))

    def warm_line():
        prev = None
        for x in line:
            prev = robot.equilibrium(pose=x, start=prev)
    add("statics, line, cold", lambda: [robot.equilibrium(pose=x) for x in line], len(line))
    add("statics, line, warm", warm_line, len(line))
    with brent_statics():
        add("statics, line, per-cable Brent (first)",
            lambda: [robot.equilibrium(pose=x) for x in line[:5]], 5, 1)
    add("statics, grid (warm along chunks)", lambda: chunked_statics(robot, X, chunk), len(X))
    with previous_statics():
        add("statics, grid, numpy Newton + LP (before)", lambda: chunked_statics(robot, X, chunk),
            len(X))
    add("statics + 20 modes + checks, grid (map)", lambda: map_chunks(robot, X, chunk), len(X))
    with previous_statics():
        add("  the same, numpy Newton + LP (before)", lambda: map_chunks(robot, X, chunk), len(X))

    def full():
        for x in line[:5]:
            ds.modes(ds.build_model(robot.equilibrium(pose=x), "dsm"), n_modes=N_MODES)
    add("statics + dynstiff.modes(20), line", full, 5, 1)
    return rows


def children_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def throughput(robot, grid, chunk, use_dask):
    """Wall and CPU time of a map of the grid: serial, 2 local processes, Dask LocalCluster.
    Rows: name -> (poses, wall s, feasible, CPU s of this process + its children, load)."""
    kw = {"n_modes": N_MODES, "band_hz": BAND, "chunk_size": chunk}
    ds.workspace(robot, grid[:2], **kw)             # xarray and the kernels loaded first
    out = {}
    runs = [("serial", {}), ("2 local processes", {"workers": 2})]
    for name, extra in runs:
        t, c, cc = time.perf_counter(), time.process_time(), children_cpu()
        m = ds.workspace(robot, grid, **kw, **extra)
        out[name] = (len(grid), time.perf_counter() - t, int(m["feasible"].sum()),
                     time.process_time() - c + children_cpu() - cc, load())
    if use_dask:
        from distributed import Client, LocalCluster
        with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                          dashboard_address=None) as cluster, Client(cluster) as client:
            t = time.perf_counter()
            m = ds.workspace(robot, grid, client=client, **kw)
            out["Dask LocalCluster, 2 workers"] = (len(grid), time.perf_counter() - t,
                                                   int(m["feasible"].sum()), None, load())
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--poses", type=int, default=300, help="grid size of the map")
    ap.add_argument("--repeats", type=int, default=3, help="repeats of the CPU rows")
    ap.add_argument("--no-dask", action="store_true", help="skip the Dask cluster")
    args = ap.parse_args(argv)
    robot = ds.load_scene("cogiro").robot
    grid = grid_of_poses(args.poses)
    chunk = max(5, len(grid) // 16)
    print(f"OPENBLAS_NUM_THREADS={os.environ.get('OPENBLAS_NUM_THREADS')}, "
          f"{os.cpu_count()} CPUs, grid {len(grid)} poses in chunks of {chunk}")
    rows = cpu_rows(robot, grid, chunk, args.repeats)
    base = {n: v for n, v, _ in rows}["statics + 20 modes + checks, grid (map)"]
    print(f"\n{'CPU per CoGiRo pose (least of repeats)':<44s} {'ms':>8s} {'/ map':>7s} "
          f"{'load':>5s}")
    for name, v, ld in rows:
        print(f"{name:<44s} {v:8.2f} {v / base:7.2f} {ld:5.1f}")
    print(f"\n{'workspace map (grid, 20 modes)':<30s} {'poses':>6s} {'feasible':>8s} "
          f"{'wall s':>7s} {'poses/s':>8s} {'CPU s':>6s} {'10k wall [s]':>12s} {'load':>5s}")
    res = throughput(robot, grid, chunk, not args.no_dask)
    for name, (n, dt, nf, cpu, ld) in res.items():
        print(f"{name:<30s} {n:6d} {nf:8d} {dt:7.2f} {n / dt:8.1f} "
              f"{'' if cpu is None else f'{cpu:.2f}':>6s} {1e4 * dt / n:12.0f} {ld:5.1f}")
    n, _, _, cpu1, _ = res["serial"]
    _, dt2, _, cpu2, _ = res["2 local processes"]
    over = cpu2 - cpu1
    print(f"\n2-process pool: {over:+.2f} s CPU beyond the serial run ({100 * over / cpu1:+.1f} %),"
          f" efficiency serial CPU / (2 x wall) = {cpu1 / (2 * dt2):.2f}")
    print("10,000 poses on 2 idle cores, (CPU + the pool's extra CPU, scaled) / 2:")
    print(f"  from the least map CPU above, {base:.2f} ms per pose: "
          f"{1e4 * (base * 1e-3 + max(over, 0.0) / n) / 2:.0f} s")
    print(f"  from this serial run's CPU, {1e3 * cpu1 / n:.2f} ms per pose: "
          f"{1e4 * (cpu1 + max(over, 0.0)) / n / 2:.0f} s")
    return rows, res


if __name__ == "__main__":
    main()
