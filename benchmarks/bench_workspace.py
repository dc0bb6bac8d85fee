"""Benchmark: CoGiRo workspace maps (goals: 10,000 poses with the first 20 modes and every
check in 20 s of wall time on 2 cores, i.e. 3.5 ms of CPU a pose; first targets per pose:
inverse statics <= 5 ms CPU, statics + 20 modes <= 12 ms CPU).

Measured (2 cores, the other one busy, least of 3, ``--per-pose --poses 343 --against
51e2086``): a pose with the forbidden band 13.08 ms -> 5.19 ms, without it 9.59 ms -> 4.12
ms (theory.md §13.7); the 3.5 ms goal is not reached. Later (``--against 9ad3ef2``, the
same run, 2 mutation runs on the machine): the model's build 0.85 -> 0.72 ms (lever maps
written entry by entry, the static error's J^T K J by matmul on the build's own lever maps,
the platform mass computed once), a pose 4.73 -> 4.64 ms with the band, 3.86 -> 3.67 ms
without, maps identical to the bit. Where the rest goes is spread thin: a cProfile of the
map shows no Python function above 0.12 ms a pose (profiled); the compiled kernels (search,
count, receptance, stiffness, statics' fixed point) take about 1.5 ms of it. Then (theory.md
§13.7, "Then"): 4.23 -> 3.70 ms with the band, 3.41 -> 2.96 ms without; and measured, not
projected (``--ten-thousand --against f54db41``, 2 local processes, one run): 10,648 poses
in 18.4 s of wall (17.2 s per 10,000 poses, 3.41 ms of CPU a pose, workers and parent)
against 73.3 s (68.8 s per 10,000, 13.66 ms a pose) at f54db41. The projection below scales the
pool's extra CPU of a small map (mostly the workers' start) to 10,000 poses: 23 s.
Measured again later (``--ten-thousand --against 2b8cc54``, load 1.4-1.5): 10,648 poses in
19.5 s (18.3 s per 10,000, 3.64 ms of CPU a pose) against 20.4 s at 2b8cc54; and
``--per-pose --against c0371f8`` (the code of the 17.2 s figure) in one run: 3.90 against
3.86 ms with the band, 3.20 against 3.13 ms without, maps identical (the machine about 4 %
slower than in that run, theory.md §13.7).

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

``--ten-thousand`` measures instead of projecting: the wall time of a map of ``--poses``
(default 10,000) grid poses on 2 local processes, with ``--against REV`` side by side (each
in a fresh interpreter, alternated), the least of ``--repeats``.

``--per-pose`` prints only the cost of a map per pose (``dynstiff.workspace``, serial, 20
modes and every check; the grid of ``--poses``), with the forbidden band (0, 1.5) Hz and
without it, and where it goes (cProfile: statics, model, damped model, platform modes,
receptance, cable model, sag, the rest; each stage's share of the profiled run times the
unprofiled CPU time). ``--against REV`` measures a git revision of this repository the same
way, side by side in the same run (each measurement in a fresh interpreter, the two trees
alternated, the least of ``--repeats``), and says whether both trees give the same map
(feasibility, verdicts; frequencies to the largest relative difference).
"""

import argparse
import cProfile
import json
import os
import pstats
import resource
import subprocess
import sys
import tempfile
import time
from contextlib import contextmanager

import numpy as np

import dynstiff as ds
from dynstiff.analyses.checks import check_options
from dynstiff.maps.workspace import CHECKS, evaluate_chunk
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
    """Inverse statics as before theory.md §13.6: the numpy loop with the numpy Newton, and
    every tension distribution that leaves the limits started from the LP's feasible
    point."""
    batched, dist = statics.taut_catenaries, statics._distribution

    def numpy_newton(*args, **kw):
        return batched(*args, **{**kw, "compiled": False})

    def lp_started(W, w, t_min, t_max, t_ref=None, sides=None):
        return dist(W, w, t_min, t_max, t_ref, warm=False)
    fixed = statics._compiled_fixed_point
    statics.taut_catenaries, statics._distribution = numpy_newton, lp_started
    statics._compiled_fixed_point = lambda *a, **k: None          # the numpy loop
    try:
        yield
    finally:
        statics.taut_catenaries, statics._distribution = batched, dist
        statics._compiled_fixed_point = fixed


@contextmanager
def brent_statics():
    """Inverse statics with every cable handed to the scalar bracketing solver."""
    batched = statics.taut_catenaries

    def scalar_only(anchors, ends, tensions, EA, w0, start=None):
        nan = np.full(len(tensions), np.nan)
        return nan, nan.copy(), nan.copy(), nan.copy(), np.ones(len(tensions), bool)
    fixed = statics._compiled_fixed_point
    statics.taut_catenaries = scalar_only
    statics._compiled_fixed_point = lambda *a, **k: None          # the numpy loop
    try:
        yield
    finally:
        statics.taut_catenaries = batched
        statics._compiled_fixed_point = fixed


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
    options = check_options(BAND)
    for s in range(0, len(X), chunk):
        evaluate_chunk(robot, X[s:s + chunk], N_MODES, options, "dsm", ds.Damping(), {},
                       CHECKS)


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


ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
#: Stages of a pose: (label, function names; a name "f<g" is f where g called it).
STAGES = (("statics", ("tension_equilibrium",)),
          ("statics rows + sag", ("statics_rows", "equilibrium_sag_ratios<evaluate_chunk",
                                  "equilibrium_sag_ratios<_evaluate_pose")),
          ("model", ("build_model<evaluate_chunk", "build_model<_evaluate_pose")),
          ("damped model", ("damped_model",)),
          ("platform modes", ("find_platform_modes",)),
          ("receptance in band", ("receptance_amplification",)),
          ("cable model error", ("estimated_error",)),
          ("proximity", ("proximity_warnings",)))


def _stage_times(stats):
    """{stage: cumulative profiled s} and the profiled s of evaluate_chunk."""
    by_name = {}
    for (_, _, name), (_, _, _, ct, callers) in stats.stats.items():
        by_name.setdefault(name, []).append((ct, callers))
    out = {}
    for label, names in STAGES:
        t = 0.0
        for n in names:
            f, _, caller = n.partition("<")
            for ct, callers in by_name.get(f, []):
                t += ct if not caller else sum(v[3] for (_, _, g), v in callers.items()
                                               if g == caller)
        out[label] = t
    total = sum(ct for ct, _ in by_name.get("evaluate_chunk", []))
    return out, total


def per_pose_child(n_poses, chunk, profile, dump):
    """In a fresh interpreter: CPU ms per pose of a serial map with and without the band,
    the stage breakdown (profile) and the map's arrays (dump, .npz). Prints JSON."""
    robot = ds.load_scene("cogiro").robot
    X = grid_of_poses(n_poses)
    kw = {"n_modes": N_MODES, "chunk_size": chunk}
    ds.workspace(robot, X[:3], band_hz=BAND, **kw)   # kernels and modules loaded first
    out = {}
    for name, band in (("band", BAND), ("no band", None)):
        t = time.process_time()
        m = ds.workspace(robot, X, band_hz=band, **kw)
        res = {"ms": 1e3 * (time.process_time() - t) / len(X), "load": load(),
               "poses": len(X), "feasible": int(m["feasible"].sum()),
               "dynamic": int(m["dynamic"].sum())}
        if profile:
            pr = cProfile.Profile()
            pr.runcall(ds.workspace, robot, X, band_hz=band, **kw)
            stages, total = _stage_times(pstats.Stats(pr))
            res["stages"] = {k: v / total for k, v in stages.items()}
        if dump:
            np.savez(f"{dump}-{name.replace(' ', '_')}.npz",
                     **{k: m[k].values for k in ("feasible", "passed", "unknown", "freq",
                                                 "first_platform_hz", "band_margin",
                                                 "tension")})
        out[name] = res
    print(json.dumps(out))


def _export(rev, where):
    """The package of git revision ``rev`` in folder ``where``."""
    tar = subprocess.run(["git", "-C", ROOT, "archive", rev, "dynstiff"], check=True,
                         capture_output=True).stdout
    os.makedirs(where, exist_ok=True)
    subprocess.run(["tar", "-x", "-C", where], input=tar, check=True)
    return where


def _in_tree(tree, *args):
    """This script run with ``args`` in a fresh interpreter on the package of ``tree``
    (single-threaded BLAS): the JSON of its last printed line."""
    env = {**os.environ, "PYTHONPATH": tree, "OPENBLAS_NUM_THREADS": "1"}
    run = subprocess.run([sys.executable, os.path.abspath(__file__), *map(str, args)], env=env,
                         check=True, capture_output=True, text=True)
    return json.loads(run.stdout.strip().splitlines()[-1])


def _alternated(trees, repeats, measure):
    """{tree name: [measure(name, path, repeat) for each repeat]}, the trees taken in
    alternating order from one repeat to the next (so that a drift of the machine's load
    favours neither)."""
    runs = {name: [] for name, _ in trees}
    for r in range(repeats):
        for name, path in (trees if r % 2 == 0 else trees[::-1]):
            runs[name].append(measure(name, path, r))
    return runs


def _trees(against, tmp):
    """[(name, package folder)]: this tree, and git revision ``against`` exported to ``tmp``."""
    trees = [("this tree", ROOT)]
    if against:
        trees.append((against, _export(against, os.path.join(tmp, "rev"))))
    return trees


def _child(tree, n_poses, chunk, profile, dump):
    return _in_tree(tree, "--child", "--poses", n_poses, "--chunk", chunk,
                    *(["--profile"] if profile else []), *(["--dump", dump] if dump else []))


def _same_map(a, b):
    """In words: do two dumped maps agree (feasibility and verdicts exactly, numbers to
    their largest relative difference)?"""
    A, B = np.load(a), np.load(b)
    same = all(np.array_equal(A[k], B[k]) for k in ("feasible", "passed", "unknown"))
    rel = {}
    for k in ("freq", "first_platform_hz", "tension"):
        x, y = A[k], B[k]
        if not np.array_equal(np.isnan(x), np.isnan(y)):
            return "NaNs differ in " + k
        f = ~np.isnan(x)
        rel[k] = float(np.max(np.abs(x[f] / y[f] - 1.0), initial=0.0))
    d = np.nanmax(np.abs(A["band_margin"] - B["band_margin"]), initial=0.0)
    return (("feasibility and verdicts identical" if same else "VERDICTS DIFFER")
            + "; largest relative difference: " + ", ".join(f"{k} {v:.1e}" for k, v in
                                                            rel.items())
            + f", band margin {d:.1e} absolute")


def per_pose(n_poses, repeats, against):
    """The per-pose table, this tree and (optionally) revision ``against`` side by side."""
    chunk = 25
    n = len(grid_of_poses(n_poses))
    print(f"OPENBLAS_NUM_THREADS=1, {os.cpu_count()} CPUs; CoGiRo map of {n} grid poses "
          f"over the frame, {N_MODES} modes, chunks of {chunk}, serial; CPU ms per pose, "
          f"least of {repeats}", flush=True)
    with tempfile.TemporaryDirectory() as tmp:
        trees = _trees(against, tmp)

        def measure(name, path, r):
            dump = os.path.join(tmp, f"map0-{name.replace(' ', '_')}") if r == 0 else None
            return _child(path, n_poses, chunk, r == 0, dump)
        runs = _alternated(trees, repeats, measure)
        cases = ("band", "no band")
        best = {name: {c: min(x[c]["ms"] for x in rs) for c in cases}
                for name, rs in runs.items()}
        names = [name for name, _ in trees]
        head = f"{'':<22s}" + "".join(f"{f'{nm}, {c}':>24s}" for nm in names for c in cases)
        print(head)
        print(f"{'ms per pose':<22s}" + "".join(f"{best[nm][c]:24.2f}" for nm in names
                                                 for c in cases))
        for label, _ in STAGES:
            print(f"{'  ' + label:<22s}" + "".join(
                f"{runs[nm][0][c]['stages'][label] * best[nm][c]:24.2f}"
                for nm in names for c in cases))
        print(f"{'  rest':<22s}" + "".join(
            f"{(1 - sum(runs[nm][0][c]['stages'].values())) * best[nm][c]:24.2f}"
            for nm in names for c in cases))
        loads = [x[c]["load"] for rs in runs.values() for x in rs for c in cases]
        r0 = runs[names[0]][0]
        print(f"(stages: cProfile shares x the unprofiled CPU; load {min(loads):.1f}-"
              f"{max(loads):.1f}; feasible {r0['band']['feasible']} of {n}, dynamic "
              f"workspace {r0['band']['dynamic']} with the band, {r0['no band']['dynamic']} "
              f"without)")
        if against:
            for c in cases:
                print(f"{c}: {against} / this tree = {best[against][c] / best[names[0]][c]:.2f}"
                      f"x; " + _same_map(os.path.join(tmp, f"map0-this_tree-"
                                                            f"{c.replace(' ', '_')}.npz"),
                                         os.path.join(tmp, f"map0-{against}-"
                                                           f"{c.replace(' ', '_')}.npz")))
    return runs


def ten_thousand_child(n_poses):
    """In a fresh interpreter: wall and CPU time (this process and its workers) of a CoGiRo
    map of about ``n_poses`` grid poses on 2 local processes, 20 modes, every check and the
    forbidden band, the default chunks. Prints JSON."""
    robot = ds.load_scene("cogiro").robot
    X = grid_of_poses(n_poses)
    kw = {"n_modes": N_MODES, "band_hz": BAND}
    ds.workspace(robot, X[:2], **kw)                # kernels and modules loaded first
    t, c, cc = time.perf_counter(), time.process_time(), children_cpu()
    m = ds.workspace(robot, X, workers=2, **kw)
    print(json.dumps({"poses": len(X), "wall": time.perf_counter() - t,
                      "cpu": time.process_time() - c + children_cpu() - cc,
                      "feasible": int(m["feasible"].sum()), "load": load()}))


def ten_thousand(n_poses, repeats, against):
    """The 10,000-pose goal measured, not projected: the wall time of a map of about
    ``n_poses`` poses on 2 local processes, this tree and (optionally) revision ``against``
    alternated in fresh interpreters, the least of ``repeats``, scaled to 10,000 poses."""
    with tempfile.TemporaryDirectory() as tmp:
        runs = _alternated(_trees(against, tmp), repeats, lambda name, path, r: _in_tree(
            path, "--ten-thousand-child", "--poses", n_poses))
        print(f"CoGiRo map on 2 local processes (20 modes, every check, band {BAND} Hz), "
              f"least wall of {repeats}:")
        for name, rs in runs.items():
            b = min(rs, key=lambda x: x["wall"])
            print(f"  {name:<12s} {b['poses']} poses ({b['feasible']} feasible): wall "
                  f"{b['wall']:.1f} s, {1e4 * b['wall'] / b['poses']:.1f} s per 10,000 poses; "
                  f"CPU {b['cpu']:.1f} s ({1e3 * b['cpu'] / b['poses']:.2f} ms a pose, "
                  f"workers and parent); load {max(x['load'] for x in rs):.1f}")
    return runs


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--poses", type=int, default=None,
                    help="grid size of the map (default 300; 10,000 with --ten-thousand)")
    ap.add_argument("--repeats", type=int, default=3, help="repeats of the CPU rows")
    ap.add_argument("--no-dask", action="store_true", help="skip the Dask cluster")
    ap.add_argument("--per-pose", action="store_true",
                    help="only the per-pose cost with and without the band, by stage")
    ap.add_argument("--against", metavar="REV",
                    help="with --per-pose or --ten-thousand: a git revision measured side "
                         "by side")
    ap.add_argument("--ten-thousand", action="store_true",
                    help="measure the wall time of a map of --poses poses (default here "
                         "10,000) on 2 local processes, with --against side by side")
    ap.add_argument("--ten-thousand-child", action="store_true", help=argparse.SUPPRESS)
    ap.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    ap.add_argument("--chunk", type=int, default=25, help=argparse.SUPPRESS)
    ap.add_argument("--profile", action="store_true", help=argparse.SUPPRESS)
    ap.add_argument("--dump", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.poses is None:
        args.poses = 10_000 if args.ten_thousand else 300
    if args.ten_thousand_child:
        return ten_thousand_child(args.poses)
    if args.ten_thousand:
        return ten_thousand(args.poses, args.repeats, args.against)
    if args.child:
        return per_pose_child(args.poses, args.chunk, args.profile, args.dump)
    if args.per_pose:
        return per_pose(args.poses, args.repeats, args.against)
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
