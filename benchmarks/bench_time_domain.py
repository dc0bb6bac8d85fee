"""Benchmark: time-domain simulation speed of the lumped-mass model, in simulated seconds per
wall-clock second, beside MoorDyn for a single line.

Cases
-----
* CoGiRo (scene ``cogiro``, lengths of ``scene.equilibrium()``), N = 20 per cable, free
  vibration after a 0.1 mm / 0.1 mrad offset: implicit (Newmark, dt = 1 ms) and explicit
  (velocity Verlet at 0.9 x its predicted stability limit, theory.md §7.3).
* One CoGiRo cable (anchor a_0, 300 N at B, 20 segments) ending on a 1-DOF vertical slider
  whose mass the cable carries, driven by a 2 N, 2 Hz vertical force; axial dashpot
  c_ax = 23.6 N s (damping ratio 0.5 on the highest axial chain mode; MoorDyn's RK2 goes to
  NaN without it). dynstiff implicit at dt = 1, 2.5 and 5 ms, explicit at 0.9 x its limit.
* The same line in MoorDyn (``pip install moordyn``; optional, not a dependency): a v2 input
  file in air (rho 0), RK2 at dtM = 0.3 ms (its largest stable step here: 0.5 ms gives NaN),
  anchor ``Fixed``, B ``Coupled`` and driven every 1 ms with the slider motion computed by
  the dynstiff run. "tension diff" is the RMS difference of the fairlead-tension fluctuation
  (mean removed: MoorDyn's FairTen is the net end-node force, ours the last segment's
  tension) between MoorDyn and dynstiff under the same motion of B: the two codes integrate
  the same lumped line, so it measures the accuracy reached at each dt.

Run:  python benchmarks/bench_time_domain.py
"""

import contextlib
import os
import sys
import tempfile
import time

import numpy as np

import dynstiff as ds
from dynstiff.lumped import LumpedMassModel, TimeDamping, explicit_step_limit, simulate

A0 = np.array([-7.1775, -5.4361, 5.3911])          # CoGiRo anchor a_0 (Table I) [m]
B0 = np.array([0.5032, -0.4928, 1.0])              # b_0 with the platform at (0, 0, 1) m
CABLE = ds.Cable(0.064, 8.2051e-6 * 17e9)          # 4 mm steel, E = 17 GPa
C_AX = 23.6                                        # axial dashpot [N s]
MOORDYN_DTM = 3e-4                                 # MoorDyn RK2 internal step [s]


def cogiro_cases(N=20, t_impl=1.0, t_expl=0.2):
    scene = ds.load_scene("cogiro")
    m = LumpedMassModel(scene.robot, scene.equilibrium().unstretched_lengths, segments=N)
    start = m.equilibrium()
    offset = [1e-4, -1e-4, 1e-4, 1e-4, -1e-4, 1e-4]
    rows = []
    r = simulate(m, t_impl, 1e-3, initial=offset, record_every=10, start=start)
    rows.append((f"CoGiRo N={N}", "dynstiff implicit", 1e-3, r.speed_ratio,
                 np.abs(r.energy.relative_residual).max(), np.nan))
    dt = 0.9 * explicit_step_limit(m)
    r = simulate(m, t_expl, dt, scheme="explicit", initial=offset, record_every=50,
                 start=start)
    rows.append((f"CoGiRo N={N}", "dynstiff explicit", dt, r.speed_ratio,
                 np.abs(r.energy.relative_residual).max(), np.nan))
    return rows


def line_model(N=20):
    st = ds.unstretched_length_for_tension(A0, B0, 300.0, CABLE)
    slider = ds.Platform(st.force_on_end[2] / ds.STANDARD_GRAVITY, free_dofs=("z",))
    robot = ds.Robot(A0[None, :], np.zeros((1, 3)), CABLE, slider)
    m = LumpedMassModel(robot, [st.unstretched_length], segments=N)
    return m, m.equilibrium(initial_pose=B0)


def _force(t):
    return np.array([0.0, 0.0, 2.0 * np.sin(2 * np.pi * 2.0 * t), 0.0, 0.0, 0.0])


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


def moordyn_line(motion, N=20, dtm=MOORDYN_DTM, coupling_dt=1e-3):
    """MoorDyn run of the line with B driven by ``motion`` (a TimeResponse); returns
    (simulated s per wall s, fairlead tension history at the coupling steps) or None."""
    try:
        import moordyn
    except ImportError:
        return None
    shift = -10.0                                   # keep the line below MoorDyn's z = 0
    L0 = motion.unstretched_lengths[0, 0]
    text = "\n".join([
        "--------------------- MoorDyn Input File ------------------------------------",
        "dynstiff benchmark: one CoGiRo cable in air",
        "---------------------- LINE TYPES --------------------------------------------",
        "TypeName Diam Mass/m EA BA/-zeta EI Cd Ca CdAx CaAx",
        "(name) (m) (kg/m) (N) (N-s/-) (N-m^2) (-) (-) (-) (-)",
        f"steel 0.004 {CABLE.mass_per_length:.10g} {CABLE.EA:.10g} {C_AX:.10g} 0 0 0 0 0",
        "---------------------- POINTS ------------------------------------------------",
        "ID Attachment X Y Z Mass Volume CdA Ca",
        "(#) (word) (m) (m) (m) (kg) (m^3) (m^2) (-)",
        "1 Fixed {:.10g} {:.10g} {:.10g} 0 0 0 0".format(*(A0 + [0.0, 0.0, shift])),
        "2 Coupled {:.10g} {:.10g} {:.10g} 0 0 0 0".format(*(B0 + [0.0, 0.0, shift])),
        "---------------------- LINES -------------------------------------------------",
        "ID LineType AttachA AttachB UnstrLen NumSegs LineOutputs",
        "(#) (name) (ID) (ID) (m) (-) (-)",
        f"1 steel 1 2 {L0:.15g} {N} -",
        "---------------------- OPTIONS -----------------------------------------------",
        f"{dtm} dtM", "rk2 tScheme", f"{ds.STANDARD_GRAVITY} g", "0.0 rho", "100 WtrDpth",
        "0 writeLog", "1 disableOutput", "1 disableOutTime",
        "------------------------- need this line -------------------------------------",
        ""])
    with tempfile.TemporaryDirectory() as tmp, _c_output_silenced():
        path = os.path.join(tmp, "line.txt")
        with open(path, "w") as f:
            f.write(text)
        system = moordyn.Create(path)
        times = np.arange(0.0, motion.times[-1] + 1e-12, coupling_dt)
        z = np.interp(times, motion.times, motion.pose[:, 2]) + shift
        vz = np.interp(times, motion.times, motion.velocity[:, 2])
        xy = [float(B0[0]), float(B0[1])]
        moordyn.Init(system, xy + [float(z[0])], [0.0, 0.0, float(vz[0])])
        line = moordyn.GetLine(system, 1)
        tension = np.empty(times.size)
        tension[0] = moordyn.GetLineFairTen(line)
        t0 = time.perf_counter()
        for k in range(1, times.size):
            # MoorDyn takes the coupled state at the start of the step and moves the point
            # with that velocity over the step (passing the end state lags by one step)
            moordyn.Step(system, xy + [float(z[k - 1])], [0.0, 0.0, float(vz[k - 1])],
                         float(times[k - 1]), coupling_dt)
            tension[k] = moordyn.GetLineFairTen(line)
        wall = time.perf_counter() - t0
        moordyn.Close(system)
    return times[-1] / wall, times, tension


def _tension_diff(r, times, tension):
    ours = np.interp(times, r.times, r.end_tensions[:, 0])
    return float(np.sqrt(np.mean(((ours - ours.mean()) - (tension - tension.mean())) ** 2)))


def line_cases(N=20, t_end=5.0):
    m, start = line_model(N)
    damping = TimeDamping(axial=C_AX)
    rows = []
    runs = []
    for dt in (1e-3, 2.5e-3, 5e-3):
        r = simulate(m, t_end, dt, excitation=_force, damping=damping, start=start)
        runs.append(("dynstiff implicit", dt, r))
    dt = 0.9 * explicit_step_limit(m, damping=damping)
    r = simulate(m, t_end, dt, excitation=_force, damping=damping, record_every=3,
                 start=start)
    runs.append(("dynstiff explicit", dt, r))
    md = None
    for name, dt, r in runs:
        res = moordyn_line(r, N)
        diff = np.nan
        if res is not None:
            md = res
            diff = _tension_diff(r, res[1], res[2])
        rows.append((f"line N={N}", name, dt, r.speed_ratio,
                     np.abs(r.energy.relative_residual).max(), diff))
    if md is not None:
        rows.append((f"line N={N}", "MoorDyn RK2", MOORDYN_DTM, md[0], np.nan, 0.0))
    return rows, md is not None, float(np.std(runs[0][2].end_tensions[:, 0]))


def main():
    rows = cogiro_cases()
    line_rows, have_moordyn, t_std = line_cases()
    rows += line_rows
    print(f"{'case':<14s} {'code / scheme':<20s} {'dt [s]':>9s} {'sim s / wall s':>15s} "
          f"{'energy res':>11s} {'tension diff [N]':>17s}")
    for case, name, dt, speed, res, diff in rows:
        print(f"{case:<14s} {name:<20s} {dt:9.2e} {speed:15.3f} {res:11.1e} {diff:17.4f}")
    print(f"(fairlead tension fluctuation of the line: std {t_std:.3f} N)")
    if not have_moordyn:
        print("MoorDyn is absent (pip install moordyn): no side-by-side line run")
    return rows


if __name__ == "__main__":
    main()
