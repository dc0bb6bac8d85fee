"""Benchmark: time-domain throughput of the lumped-mass model beside MoorDyn, each code at its
largest time step that stays within a stated accuracy of its own fine-step run.

Cases (equal segments, N = 20 per cable, ``T_END`` = 10 s simulated by default)
--------------------------------------------------------------------------------
* **line**: one CoGiRo cable (anchor a_0, 300 N at B) ending on a 1-DOF vertical slider whose
  mass the cable carries, driven by a 2 N, 2 Hz vertical force; axial dashpot c_ax = 23.6 N s
  (damping ratio 0.5 on the highest axial chain mode; MoorDyn's RK2 goes to NaN without
  it). Signal: the fairlead tension. MoorDyn integrates the same line with B ``Coupled`` and
  driven every 1 ms with the slider motion of the dynstiff fine-step run.
* **CoGiRo** (scene ``cogiro``, lengths of ``scene.equilibrium()``): 8 cables and the
  6-DOF platform in free vibration after a 0.1 mm / 0.1 mrad offset, the same dashpots.
  Signal: the platform pose (6 components). MoorDyn: a ``Free`` body (its input takes the
  diagonal of the inertia only), anchors ``Fixed``, attachments on ``Body1``, driven in
  steps of 1 ms.

Accuracy: the RMS difference of the signal from the code's own fine-step run, relative to
the RMS fluctuation of that run (``TOLERANCE`` = 2 %). dynstiff implicit (Newmark, the
compiled run with numba) at several dt against its fine run at 0.25 ms; dynstiff explicit
(velocity Verlet, the compiled run) at fractions ``EXPLICIT_FRACTIONS`` of its predicted
stability limit against its own fine run at ``EXPLICIT_FINE`` of the limit; MoorDyn RK2 at
several dtM (larger ones give NaN) against its fine run at dtM / 4 of the smallest. The two
dynstiff fine runs are compared with each other as a check of the physics. Every run covers
the whole ``t_end``.

Speed: simulated seconds per wall second, the best of ``REPEATS`` runs (the machine may be
shared). dynstiff: the whole ``simulate`` call (start, initial offset, stepping, records) plus
the evaluation of the load table; MoorDyn: its stepping loop only (input parsing and Init
excluded). The numba kernels are compiled (or loaded from the on-disk cache) by a warm-up run
before any timing. The summary gives, per case, each code's fastest run within the tolerance
and the ratio dynstiff / MoorDyn (goal >= 1). Run with OPENBLAS_NUM_THREADS=1.

Run:  python benchmarks/bench_time_domain.py [t_end [repeats]]
(MoorDyn: pip install "dynstiff[benchmark]")
"""

import contextlib
import os
import sys
import tempfile
import time

import numpy as np

import dynstiff as ds
from dynstiff.lumped import (
    IntegrationError,
    LumpedMassModel,
    TimeDamping,
    explicit_step_limit,
    simulate,
)

A0 = np.array([-7.1775, -5.4361, 5.3911])          # CoGiRo anchor a_0 (Table I) [m]
B0 = np.array([0.5032, -0.4928, 1.0])              # b_0 with the platform at (0, 0, 1) m
CABLE = ds.Cable(0.064, 8.2051e-6 * 17e9)          # 4 mm steel, E = 17 GPa
C_AX = 23.6                                        # axial dashpot [N s]
N_SEG = 20
T_END = 10.0
TOLERANCE = 0.02
REPEATS = 3
EXPLICIT_FRACTIONS = (1.0, 0.9, 0.75, 0.5)
EXPLICIT_FINE = 0.25
OFFSET = np.array([1e-4, -1e-4, 1e-4, 1e-4, -1e-4, 1e-4])
SHIFT = -10.0                                      # keep MoorDyn's lines below z = 0
DT_IMPLICIT = (5e-3, 2.5e-3, 1e-3, 5e-4)
DT_FINE = 2.5e-4
DTM_MOORDYN = (4e-4, 3e-4, 2e-4, 1e-4)
COUPLING = 1e-3


# ------------------------------------------------------------------------------ dynstiff
def line_model(N=N_SEG):
    st = ds.unstretched_length_for_tension(A0, B0, 300.0, CABLE)
    slider = ds.Platform(st.force_on_end[2] / ds.STANDARD_GRAVITY, free_dofs=("z",))
    robot = ds.Robot(A0[None, :], np.zeros((1, 3)), CABLE, slider)
    m = LumpedMassModel(robot, [st.unstretched_length], segments=N)
    return m, m.equilibrium(initial_pose=B0)


def cogiro_model(N=N_SEG):
    scene = ds.load_scene("cogiro")
    eq = scene.equilibrium()
    m = LumpedMassModel(scene.robot, eq.unstretched_lengths, segments=N)
    return m, m.equilibrium(), eq


def _load_table(dt, t_end):
    """The line's load at every step time k dt, as an excitation table (exact at the steps)."""
    times = np.arange(int(np.ceil(t_end / dt - 1e-9)) + 1) * dt
    loads = np.zeros((times.size, 6))
    loads[:, 2] = 2.0 * np.sin(2 * np.pi * 2.0 * times)
    return times, loads


def dynstiff_run(case, dt, t_end, scheme="implicit", repeats=1):
    """(speed [s/s], record times, signal, TimeResponse) of the fastest of ``repeats`` runs."""
    every = max(1, int(round(COUPLING / dt)))
    damping = TimeDamping(axial=C_AX)
    if case == "line":
        m, start = line_model()
    else:
        m, start, _ = cogiro_model()
    best = None
    for _ in range(repeats):
        t0 = time.perf_counter()
        if case == "line":
            r = simulate(m, t_end, dt, excitation=_load_table(dt, t_end), damping=damping,
                         scheme=scheme, record_every=every, start=start)
        else:
            r = simulate(m, t_end, dt, initial=OFFSET, damping=damping, scheme=scheme,
                         record_every=every, start=start)
        wall = time.perf_counter() - t0
        if best is None or wall < best[0]:
            best = (wall, r)
    r = best[1]
    sig = r.end_tensions[:, 0] if case == "line" else r.pose
    return r.times[-1] / best[0], r.times, sig, r


def explicit_limit(case):
    """Predicted stability limit of the explicit scheme [s] (theory.md §7.3)."""
    m = line_model()[0] if case == "line" else cogiro_model()[0]
    return explicit_step_limit(m, damping=TimeDamping(axial=C_AX))


# ------------------------------------------------------------------------------ MoorDyn
@contextlib.contextmanager
def _c_output_silenced():
    """Send the C-level stdout / stderr (MoorDyn's console log) to /dev/null."""
    sys.stdout.flush()
    sys.stderr.flush()
    saved = [os.dup(1), os.dup(2)]
    with open(os.devnull, "w") as null:
        os.dup2(null.fileno(), 1)
        os.dup2(null.fileno(), 2)
        try:
            yield
        finally:
            os.dup2(saved[0], 1)
            os.dup2(saved[1], 2)
            for fd in saved:
                os.close(fd)


def _header(title):
    return ["--------------------- MoorDyn Input File ------------------------------------",
            title,
            "---------------------- LINE TYPES --------------------------------------------",
            "TypeName Diam Mass/m EA BA/-zeta EI Cd Ca CdAx CaAx",
            "(name) (m) (kg/m) (N) (N-s/-) (N-m^2) (-) (-) (-) (-)",
            f"steel 0.004 {CABLE.mass_per_length:.10g} {CABLE.EA:.10g} {C_AX:.10g} 0 0 0 0 0"]


def _options(dtm):
    return ["---------------------- OPTIONS -----------------------------------------------",
            f"{dtm} dtM", "rk2 tScheme", f"{ds.STANDARD_GRAVITY} g", "0.0 rho",
            "100 WtrDpth", "0 TmaxIC", "0 writeLog", "1 disableOutput", "1 disableOutTime",
            "------------------------- need this line -------------------------------------",
            ""]


def _point(i, where, x):
    return "{} {} {:.10g} {:.10g} {:.10g} 0 0 0 0".format(i, where, *x)


def line_input(L0, dtm, N=N_SEG):
    return "\n".join(
        _header("dynstiff benchmark: one CoGiRo cable in air")
        + ["---------------------- POINTS ------------------------------------------------",
           "ID Attachment X Y Z Mass Volume CdA Ca",
           "(#) (word) (m) (m) (m) (kg) (m^3) (m^2) (-)",
           _point(1, "Fixed", A0 + [0.0, 0.0, SHIFT]),
           _point(2, "Coupled", B0 + [0.0, 0.0, SHIFT]),
           "---------------------- LINES -------------------------------------------------",
           "ID LineType AttachA AttachB UnstrLen NumSegs LineOutputs",
           "(#) (name) (ID) (ID) (m) (-) (-)",
           f"1 steel 1 2 {L0:.15g} {N} -"]
        + _options(dtm))


def cogiro_input(dtm, N=N_SEG):
    _, _, eq = cogiro_model(2)
    rob, p = eq.robot, eq.robot.platform
    x0 = eq.pose.position + OFFSET[:3] + [0.0, 0.0, SHIFT]
    ang = np.degrees(OFFSET[3:])                   # small angles: Euler = rotation vector
    body = ("1 Free " + " ".join(f"{v:.10g}" for v in (*x0, *ang, p.mass))
            + " {:.10g}|{:.10g}|{:.10g}".format(*p.center_of_mass)
            + " {:.10g}|{:.10g}|{:.10g}".format(*np.diag(p.inertia)) + " 0 0 0")
    lines = (_header("dynstiff benchmark: CoGiRo in air")
             + ["---------------------- BODIES ------------------------------------------------",
                "ID Attachment X0 Y0 Z0 r0 p0 y0 Mass CG* I* Volume CdA* Ca*",
                "(#) (word) (m) (m) (m) (deg) (deg) (deg) (kg) (m) (kg-m^2) (m^3) (m^2) (-)",
                body,
                "---------------------- POINTS ------------------------------------------------",
                "ID Attachment X Y Z Mass Volume CdA Ca",
                "(#) (word) (m) (m) (m) (kg) (m^3) (m^2) (-)"])
    n = rob.n_cables
    lines += [_point(i + 1, "Fixed", rob.anchors[i] + [0.0, 0.0, SHIFT]) for i in range(n)]
    lines += [_point(n + i + 1, "Body1", rob.attachments[i]) for i in range(n)]
    lines += ["---------------------- LINES -------------------------------------------------",
              "ID LineType AttachA AttachB UnstrLen NumSegs LineOutputs",
              "(#) (name) (ID) (ID) (m) (-) (-)"]
    lines += [f"{i + 1} steel {i + 1} {n + i + 1} {eq.unstretched_lengths[i]:.15g} {N} -"
              for i in range(n)]
    return "\n".join(lines + _options(dtm))


def moordyn_run(case, dtm, t_end, motion=None, repeats=1):
    """(speed [s/s], times, signal) of the fastest of ``repeats`` MoorDyn runs, NaN signal
    when it blows up; None without moordyn. ``motion``: (times, z, vz) of B for the line."""
    runs = [_moordyn_once(case, dtm, t_end, motion) for _ in range(repeats)]
    return None if runs[0] is None else max(runs, key=lambda r: r[0])


def _moordyn_once(case, dtm, t_end, motion):
    try:
        import moordyn
    except ImportError:
        return None
    times = np.arange(0.0, t_end + 1e-12, COUPLING)
    with tempfile.TemporaryDirectory() as tmp, _c_output_silenced():
        path = os.path.join(tmp, "input.txt")
        if case == "line":
            z = np.interp(times, motion[0], motion[1]) + SHIFT
            vz = np.interp(times, motion[0], motion[2])
            with open(path, "w") as f:
                f.write(line_input(line_model()[0].unstretched_lengths[0], dtm))
        else:
            with open(path, "w") as f:
                f.write(cogiro_input(dtm))
        system = moordyn.Create(path)
        xy = [float(B0[0]), float(B0[1])]
        if case == "line":
            moordyn.Init(system, xy + [float(z[0])], [0.0, 0.0, float(vz[0])])
            line = moordyn.GetLine(system, 1)
            sig = np.empty(times.size)
            sig[0] = moordyn.GetLineFairTen(line)
        else:
            moordyn.Init(system, [], [])
            body = moordyn.GetBody(system, 1)
            sig = np.empty((times.size, 6))
            sig[0] = moordyn.GetBodyState(body)[0]
        t0 = time.perf_counter()
        ok = True
        for k in range(1, times.size):
            try:
                if case == "line":
                    # the coupled state at the start of the step moves the point over it
                    moordyn.Step(system, xy + [float(z[k - 1])], [0.0, 0.0, float(vz[k - 1])],
                                 float(times[k - 1]), COUPLING)
                    sig[k] = moordyn.GetLineFairTen(line)
                else:
                    moordyn.Step(system, [], [], float(times[k - 1]), COUPLING)
                    sig[k] = moordyn.GetBodyState(body)[0]
            except Exception:                      # MoorDyn raises on NaN
                ok = False
            if not ok or not np.all(np.isfinite(sig[k])):
                sig[k:] = np.nan
                break
        wall = time.perf_counter() - t0
        moordyn.Close(system)
    if case != "line":
        sig = sig - [0.0, 0.0, SHIFT, 0.0, 0.0, 0.0]
    return times[-1] / wall, times, sig


# ------------------------------------------------------------------------------ accuracy
def relative_error(times, sig, ref_times, ref):
    """RMS difference from the fine run over the RMS fluctuation of the fine run [-]."""
    sig = np.asarray(sig, dtype=float).reshape(len(times), -1)
    ref = np.asarray(ref, dtype=float).reshape(len(ref_times), -1)
    grid = ref_times[ref_times <= times[-1] + 1e-12]
    a = np.column_stack([np.interp(grid, times, s) for s in sig.T])
    b = ref[:grid.size]
    if not np.all(np.isfinite(a)):
        return np.inf
    return float(np.sqrt(np.mean((a - b) ** 2)) / np.sqrt(np.mean((b - b.mean(axis=0)) ** 2)))


def case_rows(case, t_end, repeats=REPEATS):
    """Rows (case, code / scheme, dt, speed, error, passes) for one case, and whether MoorDyn
    ran."""
    rows = []
    limit = explicit_limit(case)
    dynstiff_run(case, DT_IMPLICIT[0], 0.02)               # compile / load the kernels
    dynstiff_run(case, limit / 2, 0.01, "explicit")
    _, t_ref, ref, r_ref = dynstiff_run(case, DT_FINE, t_end)
    rows.append((case, "dynstiff implicit (fine)", DT_FINE, r_ref.speed_ratio, 0.0, True))
    for dt in DT_IMPLICIT:
        speed, t, sig, _ = dynstiff_run(case, dt, t_end, repeats=repeats)
        err = relative_error(t, sig, t_ref, ref)
        rows.append((case, "dynstiff implicit", dt, speed, err, err <= TOLERANCE))
    _, t_ex, ref_ex, _ = dynstiff_run(case, EXPLICIT_FINE * limit, t_end, "explicit")
    err = relative_error(t_ex, ref_ex, t_ref, ref)
    rows.append((case, "dynstiff explicit (fine)", EXPLICIT_FINE * limit, np.nan, err,
                 err <= TOLERANCE))
    for frac in EXPLICIT_FRACTIONS:
        try:
            speed, t, sig, _ = dynstiff_run(case, frac * limit, t_end, "explicit", repeats)
            err = relative_error(t, sig, t_ex, ref_ex)
        except IntegrationError:
            speed, err = np.nan, np.inf
        rows.append((case, "dynstiff explicit", frac * limit, speed, err, err <= TOLERANCE))
    motion = (r_ref.times, r_ref.pose[:, 2], r_ref.velocity[:, 2]) if case == "line" else None
    fine = moordyn_run(case, min(DTM_MOORDYN) / 4, t_end, motion)
    if fine is None:
        return rows, False
    rows.append((case, "MoorDyn RK2 (fine)", min(DTM_MOORDYN) / 4, fine[0], 0.0, True))
    for dtm in DTM_MOORDYN:
        speed, t, sig = moordyn_run(case, dtm, t_end, motion, repeats)
        err = relative_error(t, sig, fine[1], fine[2])
        rows.append((case, "MoorDyn RK2", dtm, speed, err, err <= TOLERANCE))
    return rows, True


def best_rows(rows, case):
    """{code: the fastest row of the case within the tolerance (fine runs excluded)}."""
    out = {}
    for code in ("dynstiff", "MoorDyn"):
        ok = [r for r in rows if r[0] == case and r[1].startswith(code) and r[5]
              and "fine" not in r[1] and np.isfinite(r[3])]
        if ok:
            out[code] = max(ok, key=lambda r: r[3])
    return out


def main(t_end=T_END, repeats=REPEATS):
    rows, have_moordyn = [], True
    for case in ("line", "CoGiRo"):
        r, have_moordyn = case_rows(case, t_end, repeats)
        rows += r
    print(f"{t_end:g} s simulated; accuracy: RMS difference from the code's own fine run / "
          f"RMS fluctuation, tolerance {TOLERANCE:.0%}; speed: best of {repeats}")
    print(f"{'case':<7s} {'code / scheme':<26s} {'dt [s]':>9s} {'sim s / wall s':>15s} "
          f"{'rel. error':>11s} {'ok':>3s}")
    for case, name, dt, speed, err, ok in rows:
        print(f"{case:<7s} {name:<26s} {dt:9.2e} {speed:15.3f} {err:11.2e} "
              f"{'yes' if ok else 'no':>3s}")
    print("(dynstiff explicit (fine): its error is against the implicit fine run)")
    print("fastest run within the tolerance, speed, ratio dynstiff / MoorDyn:")
    for case in ("line", "CoGiRo"):
        best = best_rows(rows, case)
        for code, b in best.items():
            print(f"  {case:<7s} {code:<9s} {b[1]:<20s} dt {b[2]:.2e} s: {b[3]:8.2f} s/s")
        if len(best) == 2:
            print(f"  {case:<7s} ratio {best['dynstiff'][3] / best['MoorDyn'][3]:.2f}")
    if not have_moordyn:
        print("MoorDyn is absent (pip install \"dynstiff[benchmark]\"): no side-by-side run")
    return rows


if __name__ == "__main__":
    main(*(float(a) for a in sys.argv[1:2]), *(int(a) for a in sys.argv[2:3]))
