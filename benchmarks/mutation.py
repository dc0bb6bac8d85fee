"""Mutation testing of every module of the package (not part of CI: it takes hours on two
cores).

Run:  pip install ".[test,mutation]" && python benchmarks/mutation.py [module ...]

mutmut (configured in ``[tool.mutmut]`` of pyproject.toml: ``source_paths = ["dynstiff/"]``)
plants one small bug at a time in any module of the package and runs the tests that reach the
mutated function, in ONE child process (``--max-children 1``: the machine is shared). This
script writes the mutants first when there are none, runs mutmut and prints the score per
module (killed / (killed + survived), equivalent mutants listed in ``EQUIVALENT`` excluded),
the time the mutants' tests took per module, and every surviving mutant. ``module``
arguments restrict the run, e.g. ``dynstiff/cable/chord.py``; ``--report-only`` prints the
last run's results; ``--recheck`` runs the survivors again too, after tests were added;
``--restat`` collects again which tests reach each function (mutmut collects that map once
and adds only new tests to it: after code moved to another function or module, the moved
code is reached by no older test in the map, and its mutants survive falsely);
``--sample N`` judges a seeded uniform sample of N mutants per module (nested: a larger
sample contains a smaller one; each module has its own generator, so its sample does not
depend on the other modules) and gives each score a 95 % Wilson interval.

What mutmut cannot mutate, and why (nothing else is left out): functions with a decorator
other than ``staticmethod``/``classmethod`` (mutmut leaves them alone: its trampoline would
replace the decorated object), so the numba kernels of ``compiled/`` (``@numba.njit``:
catenary, chain, chain_run, dsm, dsm_search and statics have no mutant at all), ``compiled.load``
(``functools.cache``), properties and context managers (``io.files.atomic_path``) are not
mutated; modules without functions (``__main__``, ``_version``, ``constants``, the package
``__init__`` files) have none. ``maps/__init__`` and ``cli/__init__`` do have mutants (their
names drop ``__init__``: ``dynstiff.maps.x_register_accessor__mutmut_1``). The run prints
the modules left without mutants.

How the runs are made to work on the whole package: ``tests/test_docs_examples.py`` is left
out of mutmut's test selection (it walks the classes' attributes, where mutmut's copies of
every method appear); tests/conftest.py builds cables when it is imported, so mutmut's check
that a forced failure fails the tests (every trampoline raising) sees a failed conftest
import, a pytest usage error: ``_MUTMUT`` accepts that as the failure it is; the hypothesis
profile "mutation" (set here) does not shrink a failing example; mutmut's timeout is three
times (CPU, twice over) the clean tests' time (``timeout_multiplier = 3``; its default 15
spent up to half an hour on one hanging mutant), a timeout counting as a detection.

Measured (2 cores shared, mutmut 3.8.1, 1 child per run, ``--sample 100``, seed 20261202;
the last judgement of each sampled mutant, after the tests added for the survivors; a
module edited since is resampled from its new mutants; equivalents as stamped, below):
==================================  ======  ========  ==========  =========  ======================
module (mutants in all)             killed  survived  equivalent  unchecked  score [95 % int.]
==================================  ======  ========  ==========  =========  ======================
analyses.verdicts (442)             99      0         1           0          100 % [96.3, 100]
analyses.platform_modes (297)       93      1         5           1          98.9 % [94.2, 99.8]
analyses.checks (413)               98      0         2           0          100 % [96.2, 100]
io.files (53, all)                  52      0         1           0          100 % [93.1, 100]
analyses.measured (pairing, 576)    97      0         3           0          100 % [96.2, 100]
analyses.calibrate (836)            98      0         2           0          100 % [96.2, 100]
analyses.calibration_checks (120)   96      0         4           0          100 % [96.2, 100]
analyses.calibration_result (226)   99      0         1           0          100 % [96.3, 100]
analyses.measured_frf (391)         94      0         6           0          100 % [96.1, 100]
io.exchange (425), resampled        97      0         3           0          100 % [96.2, 100]
io.table (124)                      95      0         5           0          100 % [96.1, 100]
maps.store (137)                    92      0         8           0          100 % [96.0, 100]
maps.dataset (532)                  91      2         7           0          97.8 % [92.5, 99.4]
maps.guards (211)                   100     0         0           0          100 % [96.3, 100]
maps.arguments (362)                100     0         0           0          100 % [96.3, 100]
maps.workspace (755)                97      1         1           1          99.0 % [94.4, 99.8]
analyses.optimal_tensions (862)     93      3         4           0          96.9 % [91.2, 98.9]
cli.options (382)                   100     0         0           0          100 % [96.3, 100]
analyses.uncertainty (708)          98      1         1           0          99.0 % [94.5, 99.8]
analyses.sensitivity (881)          98      0         2           0          100 % [96.2, 100]
models.dsm_guard (271), resampled   92      1         7           0          98.9 % [94.2, 99.8]
analyses.interaction (160)          92      0         8           0          100 % [96.0, 100]
analyses.participation (364)        93      0         7           0          100 % [96.0, 100]
analyses.settings (360)             99      0         1           0          100 % [96.3, 100]
cli.common (522)                    98      0         2           0          100 % [96.2, 100]
robot.feasibility (407)             92      0         8           0          100 % [96.0, 100]
robot.distribution (473)            79      0         21          0          100 % [95.4, 100]
analyses.recommend (506)            96      1         3           0          99.0 % [94.4, 99.8]
analyses.sweep (611)                93      1         6           0          98.9 % [94.2, 99.8]
results (351)                       96      2*        2           0          98.0 % [92.9, 99.4]
analyses.frf (432)                  92      0         8           0          100 % [96.0, 100]
models.dsm (621), resampled         93      1         6           0          98.9 % [94.2, 99.8]
analyses.modes (326)                92      2*        6           0          97.9 % [92.7, 99.4]
analyses.eigen (807), resampled     86      1*        13          0          98.9 % [93.8, 99.8]
==================================  ======  ========  ==========  =========  ======================

Then 20 more modules, on a new machine (the runs above are not on its disk), the same
seed and sample size. "first pass": mutmut's judgement before any new test; "after": the
first pass's survivors killed by the tests added for them (R: confirmed by a mutmut
``--recheck``; P: by planting each mutant in a copy of the package and running the
module's own test file, mutmut's map of the tests not being rebuilt yet), named
equivalent (stamped) or left; "judged": how many of the 100 sampled mutants (all where
fewer) were run before the runs were stopped.
==============================  ======  ==================  =========================  ========
module (mutants in all)         judged  first pass k/s/e    after: killed/left/equiv.  score
==============================  ======  ==================  =========================  ========
analyses.uncertainty_result     100     47 / 53 / 0         100 / 0 / 0 (R)            100 %
robot.waypoints                 100     84 / 16 / 0         99 / 0 / 1 (R)             100 %
analyses.reduced                100     82 / 18 / 0         97 / 0 / 3 (R)             100 %
cable.guard                     100     94 / 5 / 1          96 / 0 / 4 (R)             100 %
analyses.eigen_matrix           83      74 / 26 / 0         81 / 0 / 2 (R), new src.   100 %
analyses.damped (new source)    41      35 / 6 / 0          35 / 2 / 4 (R)             94.6 %
analyses.freqgrid (70, all)     70      51 / 15 / 4         66 / 0 / 4 (P)             100 %
cable.psi (first source)        100     89 / 10 / 1         94 / 0 / 4 (P), 2 changed  100 %
cable.psi (new source)          25      24 / 0 / 1          24 / 0 / 1                 100 %
cable.catenary                  48      42 / 2 / 4          44 / 0 / 4 (P)             100 %
cable.chord                     13      13 / 0 / 0          13 / 0 / 0                 100 %
robot.pose                      28      26 / 2 / 0          28 / 0 / 0 (P)             100 %
_html (52, all)                 52      43 / 9 / 0          52 / 0 / 0 (P)             100 %
plot.common (60, all)           60      43 / 15 / 2         58 / 0 / 2 (P)             100 %
maps (__init__, 36, all)        36      0 / 36 / 0          36 / 0 / 0 (P)             100 %
cli.console (61, all)           61      48 / 13 / 0         61 / 0 / 0 (P)             100 %
scenes.writer                   100     81 / 18 / 1         99 / 0 / 1 (P)             100 %
analyses.compare_lumped         100     73 / 27 / 0         93 / 0 / 7 (P), see below  100 %
io.caspr                        100     79 / 21 / 0         99 / 0 / 1 (P), see below  100 %
timedomain.inputs               19      10 / 9 / 0          19 / 0 / 0 (P)             100 %
==============================  ======  ==================  =========================  ========

  Found on the way, and fixed: ``check_frequency_range`` let a
  real omega on a cable with heavy viscous damping through to a NaN stiffness (psi
  mutmut_27); damped_modes gave a mode its neighbour's root under heavy damping, and left
  a symmetric robot's second copy of a double mode NaN (found writing damped's tests);
  above 400 DOFs the sparse eigen solve missed an unstable equilibrium's negative
  eigenvalues (found writing eigen_matrix's tests); compare_modes' documentation said it
  pairs by |ln(f_b/f_a)| where it takes squares, which the beaded-string study needs (the
  sum of |ln| ties for close modes all shifted one way; documentation corrected); and
  the CASPR reader's inertia warning pointed one frame above its caller's line (io.caspr
  mutmut_257 and read_caspr mutmut_12 could not be killed before; both are now). The
  sources of psi, damped, eigen_matrix and compare_lumped changed with the fixes: psi,
  damped and eigen_matrix are resampled (the rows "new source"); compare_lumped's row is
  its first source, whose 7 equivalents (a zero MAC denominator with a zero numerator for
  a positive semi-definite weight, None stored as NaN, an empty assignment, += on an empty
  list, 1e+300 == 1e300) are argued but not named: the fix renumbered them. Survivors
  left: damped mutmut_144 (a multiple root's copy chosen as the first NaN copy rather than
  the mode searched: differs only for a triple mode, which no test robot has) and _54 (the
  secant's give-up radius 0.2 -> 1.2 of the estimate: no test root wanders that far).
  The timeouts counted as detections (29 in the runs of the mut worktree, under a load of
  about 4 on 2 cores) are not rechecked. Not judged yet: _vec (54), the rest of the
  samples of catenary, chord, pose, psi's new source, damped, inputs and eigen_matrix.
  Sources changed after their rows: compare_lumped (its documentation, and the relative
  difference's errstate), io.caspr (the warning's stacklevel) and damped (K at a root
  evaluated once for its residual and its shape, not twice); their equivalents are
  named on the sources judged and stamped where the code is unchanged.

Then a third round, the same seed and sample size, on the command line, the plots, the
reports and the CASPR scenes. The command-line tests had run ``python -m dynstiff`` in
subprocesses and were marked ``integration``, which this script's runs leave out: a
command's mutants met no test. They now run ``main()`` in the test's process
(``tests/conftest.py``'s ``run_cli``) and are no longer so marked (the entry point keeps
one subprocess test). The rows of the modules first run before that change (the cli
modules, report.*) are not rows of what the suite kills today; their survivors were
planted against the module's test file instead (P), which counts a mutant another file
kills as a survivor. Planting copies numba's cache folder per copy of the package
(``NUMBA_CACHE_DIR``): without it each planting compiled the kernels, 3 minutes.
==============================  ======  ==================  =========================  ========
module (mutants in all)         judged  first pass k/s/e    after: killed/left/equiv.  score
==============================  ======  ==================  =========================  ========
io.caspr_motion (276)           100     80 / 20 / 0         100 / 0 / 0 (P), then fixed  100 %
scenes.caspr (172)              100     75 / 25 / 0         100 / 0 / 0 (P)            100 %
cli (__init__) (82)             62      29 / 33 / 0         62 / 0 / 0 (P, 2 see below) 100 %
plot.accuracy (128)             100     56 / 44 / 0         98 / 0 / 2 (P), then fixed  100 %
plot.workspace (179)            100     46 / 54 / 0         98 / 0 / 2 (P), then fixed  100 %
plot.sweep (105)                100     60 / 40 / 0         94 / 0 / 6 (P)             100 %
plot.time (127)                 100     60 / 40 / 0         99 / 0 / 1 (P)             100 %
cli.exchange (173)              100     24 / 18 / 0, 58 u.  100 / 0 / 0 (P)            100 %
cli.simulate (184)              100     18 / 39 / 0, 43 u.  99 / 0 / 1 (P)             100 %
plot.modes (220)                100     54 / 46 / 0         98 / 2 / 0 (P)             98.0 %
cli.report (80)                 100     38 / 62 / 0         98 / 0 / 2 (P)             100 %
cli.sweep (186)                 100     15 / 48 / 0, 37 u.  97 / 1 / 2 (P)             99.0 %
cli.analysis (284)              100     23 / 41 / 0, 36 u.  100 / 0 / 0 (P)            100 %
cli.workspace (182)             100     28 / 25 / 0, 47 u.  not handled                --
plot.frf (141)                  100     75 / 25 / 0         not handled                --
report.robot (213)              100     54 / 46 / 0         not handled                --
report.document (115)           100     43 / 57 / 0         not handled                --
report.geometry3d (245)         100     79 / 21 / 0         not handled                --
report.cable (180)              100     28 / 72 / 0         not handled                --
==============================  ======  ==================  =========================  ========

  "u.": not judged when the run was stopped (the cli modules' first runs left their tests
  out, above); those and the survivors were planted together, so "after" covers the whole
  sample. cli (__init__): 38 of its sample were not judged; its mutmut_58 and _59 (the
  text of "interrupted") are equivalent on the source judged, which printed the exception
  object's empty text instead, a bug fixed since (the test of KeyboardInterrupt() kills
  both on the fixed source; not planted there). "then fixed": the module was edited after
  its row to fix what the new tests found (caspr_motion: time_step <= 0 or empty, two
  operational sets of one id, an axis letter twice, all refused; accuracy: a case with a
  NaN error dropped from the worst; workspace: a feasible position without its modes
  drawn in no group), so the functions edited have new mutants, not judged. plot.modes
  keeps plot_tensions mutmut_38 and _45 (the tensions read without dtype=float: they
  differ only for tensions given as text or None, which the function does not document).
  cli.sweep keeps _cmd_sweep mutmut_233 (the waypoints' legend placed "best" instead of
  upper left: the same place on the test sweeps, where the last waypoint's line crosses
  the upper right, but not for every figure). report.*
  and plot.frf were judged before the command-line tests counted: their survivors
  include what test_cli_report now kills. Not run at all this round: about 55 modules.

Then a fourth round, the same seed and sample size: a few small modules never run or run
on an older source, and two of the third round's modules not handled. mutmut judged the
first pass (the worktrees' tests of the day); the survivors were then killed by new tests
of each module's own file, each confirmed by planting (P, ``/work/wt``'s plant script: the
mutant put into a copy of the package and that one test file run), or named equivalent.
report.cable's first pass is after a ``--restat``: its command-line tests replace the
report by a spy, so they do not reach it.
==============================  ======  ==================  =========================  ========
module (mutants in all)         judged  first pass k/s/e    after: killed/left/equiv.  score
==============================  ======  ==================  =========================  ========
io.files (84, all)              84      61 / 22 / 1         83 / 0 / 1 (R)             100 %
analyses.freqgrid (64, all)     64      62 / 0 / 2          62 / 0 / 2, new source     100 %
timedomain.damping              100     88 / 12 / 0         98 / 0 / 2 (P, R in part)  100 %
robot.pose                      59      46 / 4 / 0, 9 u.    58 / 0 / 1 (P, R)          100 % of 59
scenes.writer (new source)      100     93 / 7 / 0          97 / 0 / 3 (P)             100 %
cli.console (61, all)           61      47 / 14 / 0         59 / 0 / 2 (P)             100 %
plot.frf                        100     75 / 25 / 0         98 / 0 / 2 (P)             100 %
report.cable                    100     50 / 50 / 0         97 / 0 / 3 (P)             100 %
timedomain.pendulum.dynamics    100     94 / 6 / 0          98 / 0 / 2 (P)             100 %
timedomain.pendulum.model       100     88 / 12 / 0         98 / 0 / 2 (P)             100 %
timedomain.pendulum.radau       100     89 / 11 / 0         99 / 0 / 1 (P)             100 %
timedomain.pendulum.floquet     100     82 / 18 / 0         88 / 11 / 1 (P, in part)   88.9 %
==============================  ======  ==================  =========================  ========

  timedomain.pendulum.floquet: 7 of its 18 survivors handled when the round stopped; the
  other 11 (more of _floquet_group's retries and the shooting) are left. "(R)": confirmed
  by mutmut's own recheck after the new tests; "u.": judged only after
  the new tests (all killed, or equivalent). robot.pose: 41 of its sample were not judged
  when the runs were stopped (a pose's mutant runs most of the suite). cli.console: its
  first pass counts 7 timeouts as detections (a progress bar's mutants that hang); the
  survivors were tqdm's arguments (the bar's width following the terminal) and the
  first-run notice (on a terminal only, its exact text), killed by test_cli_console, and
  tqdm's file left to its default (sys.stderr), equivalent.
  plot.frf and report.cable: their figures' and tables' visible properties (sizes, fonts,
  dash patterns, the rows and units of the statics table, the files written) were first
  documented in the functions' docstrings, then tested against that text and against
  independent values (the catenary state, the stiffness at 0 Hz). The modules edited this
  round after their rows of earlier rounds (cli.simulate, cli.sweep, cli.report,
  cli.common, plot.modes, plot.accuracy, plot.sweep, plot.workspace, scenes.caspr,
  robot.waypoints, plot.time's __all__, analyses.eigen, analyses.eigen_matrix,
  analyses.participation, analyses.platform_modes, analyses.frf, results, cable.catenary,
  robot.statics, the compiled search) have new mutants in the functions edited, not judged.

Then a fifth round, the same seed and sample size: the floquet module's last survivors and
22 modules never run. As in the fourth round, mutmut judged the first pass; each survivor
was then killed by a test of the module's own file, confirmed by planting (P) or by a
mutmut --recheck (R), or named equivalent (stamped), or left.
==============================  ======  ==================  =========================  ========
module (mutants in all)         judged  first pass k/s/e    after: killed/left/equiv.  score
==============================  ======  ==================  =========================  ========
timedomain.pendulum.floquet     100     82 / 17 / 1         98 / 0 / 2 (P)             100 %
errors (35, all)                35      26 / 9 / 0          35 / 0 / 0 (R 2, P 7)      100 %
models.static (90, all)         90      85 / 5 / 0          90 / 0 / 0 (R)             100 %
cable.modes                     100     90 / 4 / 6          94 / 0 / 6 (R)             100 %
robot.equilibrium (77, all)     77      42 / 22 / 0, 13 u.  74 / 0 / 3 (P, R)          100 %
models.base                     100     17 / 16 / 0, 67 u.  93 / 0 / 7 (R, P)          100 %
_vec (54, all)                  54      53 / 1 / 0          54 / 0 / 0 (P)             100 %
models.ladder (95, all)         95      83 / 12 / 0         95 / 0 / 0 (P)             100 %
cable.lumped_graded             100     83 / 17 / 0         91 / 0 / 9 (P), then fixed 100 %
cable.mpmath_reference          100     76 / 24 / 0         90 / 1 / 9 (P), then fixed 98.9 %
timedomain.response             100     50 / 50 / 0         96 / 0 / 4 (P)             100 %
timedomain.trajectory           100     67 / 33 / 0         99 / 1 / 0 (P)             99.0 %
timedomain.energy_scheme        100     87 / 13 / 0         99 / 0 / 1 (P)             100 %
timedomain.discrete_gradient    100     69 / 31 / 0         94 / 0 / 6 (P)             100 %
cable.lumped_elements           100     89 / 8 / 3          96 / 0 / 4 (P)             100 %
cable.lumped_chain_dynamics     100     87 / 13 / 0         93 / 0 / 7 (P), then fixed 100 %
timedomain.pendulum.maps        100     100 / 0 / 0         100 / 0 / 0                100 %
timedomain.pendulum.simulate    100     80 / 20 / 0         100 / 0 / 0 (P)            100 %
cable.catenary_batch            100     79 / 21 / 0         90 / 0 / 10 (P)            100 %
robot.forward_statics           100     89 / 11 / 0         93 / 0 / 7 (P)             100 %
cable.lumped_chain              100     86 / 12 / 2         95 / 1 / 4 (P)             99.0 %
cable.exact_condense            100     90 / 10 / 0         90 / 2 / 8                 97.8 %
cable.exact_mesh                100     94 / 2 / 4          96 / 0 / 4 (P), then fixed 100 %
==============================  ======  ==================  =========================  ========

  errors: user_stacklevel's seven survivors are killed in a plain run only: a mutation run
  puts its trampoline's frames between the package's, so the test of the levels is skipped
  there (as the other tests of warnings' places). Found on the way, and fixed ("then
  fixed"): irvine_symmetric_roots_mp returned 3 pi as the first root for lambda^2 below the
  working precision (1e-70 at 50 digits: the bracket's end values were rounding noise) and
  now returns the taut-string root, correct to more than dps digits, where the root's
  offset is below 10^-(dps+10); graded_chain raised UnboundLocalError for max_iter = 0 and
  now checks tol and max_iter; chain_end_dynamic_stiffness's pole warning printed
  "np.float64(2.0)"; exact_mesh's mesh divided the tension measure by per_efold, documented
  as elements per e-fold (the same at the default 1; now multiplied, and tested at 3;
  exact_mesh's first pass counts 73 of its mutants judged after its first new test). The
  mpmath row is the first source's sample; the root finder's new
  mutants (its taut-string branch renumbers the function's) were looked at, not sampled:
  nine survive there, seven of them likely equivalent (a precision default, <= for <, more
  bisection steps) and two (the power of psi_k in the threshold) not resolved. Survivors
  left: trajectory's _arc_length mutmut_6 (the name "length" in the message of a path
  length that overflows or underflows, from inputs no caller gives); mpmath_reference's
  _entries_to_dps mutmut_8 (at T = 0 both raise ZeroDivisionError, with another text);
  lumped_chain's chain_equilibrium mutmut_126 (the cable's weight in the Newton
  tolerance's scale taken as m g / L0, where the largest tension dominates the scale);
  exact_condense's condense mutmut_62 and _69 (the weights of the static stiffness's
  rounding-error estimate, which no test pins). Several equivalents are "in practice":
  ties of floats to the last bit, the start of an iteration that converges to the same
  point, checks of finite matrices, and catenary_batch's taut-branch test, whose three
  mutated formulas keep the sign of dT/dL0 on the 72 catenaries checked. Not run at all:
  about 30 modules (the largest: report.robot3d, timedomain.stepping,
  analyses.sensitivity_rungs, scenes.loader, cable.exact, timedomain.simulation), and the
  third round's cli.workspace, report.robot, report.document and report.geometry3d, whose
  rows predate the command-line tests counting.

Then a sixth round, the same seed and sample size: 17 modules never run. As before, mutmut
judged the first pass; each survivor was killed by a test of the module's own file,
confirmed by planting (P) or a recheck (R), or named equivalent (stamped, each stamped diff
checked against its reason), or left. "u." counts sampled mutants not judged when the run
was stopped (their share of the sample is unjudged, not passed).
=================================  ======  ==================  =========================  ======
module (mutants in all)            judged  first pass k/s/e    after: killed/left/equiv.  score
=================================  ======  ==================  =========================  ======
_html (52, all)                    52      52 / 0 / 0          52 / 0 / 0                 100 %
_validate                          71      70 / 1 / 0, 29 u.   71 / 0 / 0 (P, R)          100 %
params                             45      39 / 6 / 0, 55 u.   45 / 0 / 0 (P, R)          100 %
robot.platform, then fixed         100     95 / 2 / 3          97 / 0 / 3 (P, R)          100 %
robot.robot                        100     92 / 8 / 0          98 / 0 / 2 (P, R)          100 %
report.html                        100     70 / 30 / 0         96 / 0 / 4 (P)             100 %
models.lumped_statics              100     78 / 22 / 0         99 / 0 / 1 (P)             100 %
cable.catenary_solve               99      86 / 7 / 6, 1 u.    87 / 0 / 12 (P)            100 %
cable.dsm                          100     95 / 1 / 4          95 / 0 / 5                 100 %
scenes.loader, then fixed          100     78 / 22 / 0         95 / 0 / 5 (P)             100 %
models.exact                       100     92 / 4 / 4          92 / 0 / 8                 100 %
analyses.sensitivity_parameters    100     81 / 19 / 0         97 / 0 / 3 (P)             100 %
models.lumped                      100     82 / 18 / 0         99 / 0 / 1 (P)             100 %
models.lumped_robot                100     90 / 10 / 0         97 / 0 / 3 (P)             100 %
timedomain.dynamics                100     95 / 5 / 0          99 / 0 / 1 (P)             100 %
analyses.sensitivity_lumped        100     94 / 6 / 0          94 / 2 / 4 (not handled)   97.9 %
analyses.sensitivity_statics       100     87 / 13 / 0         94 / 3 / 3 (P)             96.9 %
=================================  ======  ==================  =========================  ======

  Found on the way and fixed, each with a test that fails on the old code: the scene
  loader gave no line for a key that follows an array spanning lines (the inertia's
  continuation rows "[-3.0, ...]]" were taken for a section header), and a 400-digit
  integer for a number raised OverflowError from numpy (now "must be a number", with its
  line); frequency_sensitivities ran the eigenfrequency search before checking
  tension_reference, hold and the parameter names, and a complex, text or wrong-length
  reference raised TypeError or ValueError from numpy (one check of the reference,
  _validate.tension_reference, now serves it and the inverse statics); the platform's
  inertia checks had an absolute floor of 1e-12 kg m^2, so a small body's verdict depended
  on its units (now relative to the tensor); plot_frf silently ignored phase=True when
  ax was given (now an error); lumped_robot's segment check had a mangled name. Untested
  before: html_page's markup (every block kind is now parsed into elements), the lumped
  equilibrium's record, its Newton's error exits and stagnation rule, the lumped linear
  model's damped K(omega) (against the closed-form spring-mass-damper and the dense Schur
  complement), the sensitivity parameters' names, units and kinds. Rows with "u." are
  partial samples (params' survivors each run most of the suite). Not handled: two
  survivors of sensitivity_lumped (forms mutmut_8, the gravity vector's x component 1
  instead of 0 in the forms' geometric stiffness: the slow tier's central-difference test
  of the lumped rung passes with it planted, its effect below that test's tolerance; and
  _98, EA / axial for EA * axial, which differ only where a segment is slack; both
  reasons were wrong, and both are killed in the ninth round, below: _8 moves the lumped
  rung's mass sensitivity by 7 %, a parameter that test leaves out, and _98 flips the
  loss factor's direction, 1 + i h, at every segment), and three
  of sensitivity_statics, each a tolerance band no caller reaches: _active_set mutmut_44
  (<= for < at a tension exactly one tolerance from t_min: the statics put held cables
  at t_min to 3e-13), _factor mutmut_18 (the pivot indices' largest, always n - 1, for
  the largest pivot in the singularity test: it moves the 1e-13 threshold by a factor 2
  to 20; the singular cases that occur have a zero pivot) and __init__ mutmut_108 (a 2 N
  floor for 1 N in the optimality check's scale: it matters only below 2 N tensions).
  Not run at all: about 15 modules (the largest: report.robot3d, timedomain.stepping,
  analyses.sensitivity_rungs, cable.exact, timedomain.simulation; also
  analyses.sensitivity_kernels, models.dsm_compiled, maps/cli/compiled __init__), and the
  third round's rows noted above.

Then a seventh round, the same seed and sample size: the modules never run, and the third
round's modules not handled. As before, mutmut judged the first pass; each survivor was
killed by a test of the module's own file (timedomain.simulation: a second file,
test_timedomain_simulation_checks.py, the first being near 500 lines), confirmed by
planting (P), or named equivalent (stamped, each stamped diff checked against its
reason), or left.
=================================  ======  ==================  =========================  ======
module (mutants in all)            judged  first pass k/s/e    after: killed/left/equiv.  score
=================================  ======  ==================  =========================  ======
analyses.sensitivity_rungs (976)   100     89 / 11 / 0         97 / 0 / 3 (P)             100 %
analyses.sensitivity_kernels       100     82 / 18 / 0         96 / 0 / 4 (P), then fixed 100 %
cable.exact, then fixed            100     92 / 5 / 3          93 / 0 / 7 (P)             100 %
models.dsm_compiled (195)          100     78 / 22 / 0         88 / 0 / 12 (P)            100 %
timedomain.stepping, then fixed    100     80 / 20 / 0         92 / 0 / 8 (P)             100 %
timedomain.simulation              100     83 / 17 / 0         99 / 0 / 1 (P)             100 %
report.robot3d (1338)              100     58 / 42 / 0         97 / 0 / 3 (P)             100 %
report.document (204)              100     45 / 55 / 0         99 / 0 / 1 (P)             100 %
cli.workspace (513)                53      35 / 18 / 0, 47 u.  49 / 0 / 4 (P)             100 %
robot.statics (813)                59      45 / 14 / 0, 41 u.  48 / 2 / 9 (P)             96.0 %
report.robot (543)                 79      48 / 31 / 0, 21 u.  75 / 1 / 3 (P)             98.7 %
=================================  ======  ==================  =========================  ======

  Found on the way and fixed, each with a test that fails on the old code: the
  sensitivity kernels' divided differences at a = b = 0 (no gravity, a horizontal chord)
  raised a RuntimeWarning from the unused branch that np.where evaluates; an excitation
  callable returning complex or text loads raised a bare TypeError, or (a complex array)
  was cut to its real part, where simulate promises InvalidParameterError naming t; and
  float frequencies do land exactly on a clamped cable pole (w^2 mu = 1 in floats: found
  for several poles of every cable tried), where ExactCable.local_coefficients and
  ExactModel's K(omega) leaked a RuntimeWarning (0 x inf in the matmul) and returned NaN
  entries undocumented (now documented as not finite there, with no warning). That last
  finding voided the reason of 12 equivalents of earlier rounds ("a float frequency next
  to a float eigenvalue does not hit w^2 mu = 1"): the errstate mutants of
  ExactCable.local_coefficients (5-8), end_response (26-29) and ExactModel._block (34-37)
  are killed now, and were removed from the equivalents; eigen._illinois mutmut_31 and
  _143 carry the same reason text, which does not fit their code (a regula falsi's
  division, not a pole), and are to be judged again. report.robot3d's figure properties
  (styles, where the mode shape is drawn, limits, ticks, size, legend, titles, the
  animation's frames) were first documented in its docstrings, then tested against them
  and against independent values; report.document's and report.robot's rows and
  paragraphs likewise. Left: robot.statics' _step_distribution mutmut_35 and _38 (the
  straight chords' first distribution with wider limits, -lo for +lo and +hi for -hi:
  only the first iterate of the fixed point, but a lower limit below zero was not shown
  harmless); report.robot's robot_report mutmut_30 (the modes searched again when the
  checks found exactly the scene's number: the same count from the same model, but the
  checks' modes were not shown identical to a new search's). Several equivalents
  are dtype arguments whose values are float64 already, or which the compiled kernels
  take in either dtype (numba compiles one more specialisation, the numbers the same).

  * results: judged on its last source (DampedModes' repr edited last); its two
  survivors were then named equivalent (an index read only for a non-empty channel) and
  killed by a new test (the FRF plot's phase off by default), not yet by a mutmut recheck.
  frf's 4 survivors of its first run were killed by new tests, confirmed by the recheck.
  models.dsm: the five survivors of the last stop were killed by new tests (the lossy
  cables' static stiffness, a cable's error below 1 rad/s, the damped copy's checks) or
  named equivalent; the module was edited since, and this row is its new sample, judged
  in full. analyses.modes: judged on its source before cable_fields' checks were added
  (modes() and the cluster basis unchanged since); its new tests killed 10 of its first 18
  survivors, 6 are named equivalent. analyses.eigen: its first run's four step-rule survivors
  are killed by the regula falsi's cost test; this row is the sample of its last source
  (after a dead errstate was removed); its one survivor, eigenfrequencies mutmut_17
  (max_modes=2.5 taken), is killed by a new case of test_bad_mode_requests_name_the_argument
  in a plain run with the mutant planted and survives under mutmut, whose map of the tests
  that reach each function holds no new parametrised case until --restat.

  First passes, before any new test: measured 79.0 %, calibrate 88.0 %, calibration_checks
  67.0 %, calibration_result 45.0 %, measured_frf 77.0 %, exchange 81.0 %, table 71.0 %,
  store 86.0 %, dataset 55.9 %, guards 80.0 %, arguments 74.0 %, workspace 72.4 %,
  optimal_tensions 76.0 %, uncertainty 66.0 %, cli.options 42.0 %, sensitivity 75.0 %,
  dsm_guard 75 %, interaction 93.6 %, participation 92.7 %, settings 86.0 %, cli.common
  66.0 %, feasibility 66.0 %, distribution 82.6 %, recommend 81.8 %, results 74.4 % (90
  of its 100 judged). Survivors that are not equivalent and stay: platform_modes
  mutmut_38 (a base taken from an empty array when no massless platform mode has a
  positive stiffness: no robot in equilibrium gives one); maps.dataset's two zarr mutants
  (zarr is not installed here, so the test of a ``.zarr`` name checks only the refusal);
  the Dask paths (maps.workspace's cancelling of futures on an interruption,
  uncertainty's submission of samples), judged only by the integration tests, which the
  mutation runs leave out; three branches of the optimal-tension search that no test
  robot reaches (the first-mode objective's cover below 1 Hz, the floor of the
  coincident-modes tolerance, a band from between 0 and 1 Hz with a mode below it);
  recommend's _dsm_error mutmut_57 (float(None) on the early return: killed by
  test_closed_form_error_in_band_and_axial_cut in a plain run with the mutant planted,
  survives under mutmut, cause not found); sweep's mutmut_270 (the tracks' renumbering by
  first frequency skipped: on the test sweeps the tracks are found in that order
  already); models.dsm's __init__ mutmut_103 (the validity computed at 1 rad/s
  instead of 0: it differs only for a cable whose first axial frequency is below 0.18 Hz;
  the five survivors of the last stop are killed or named now); dsm_guard's static_error
  mutmut_76 (the static error 1 instead of 0 when no massless mode has a positive
  stiffness: no robot in equilibrium gave one); analyses.modes' mutmut_117 and _129 (the
  on-pole test and its null tolerance: they matter at a root on a cable pole where the
  platform moves, which no test robot has).

  Equivalents are stamped with their code (``STAMPS_FILE``, ``--stamp``): mutmut numbers
  a function's mutants in order, so an edit of the function gives a number to another
  mutant. Checking every named equivalent's diff against its reason found 62 whose
  number had passed to another mutant after edits (sweep 15, closed-form model 25 (3
  more renamed to the guard's module), frf 7, catenary starts 4, modes 3, eigen 2,
  interaction 2, optimal tensions 2, end stiffness 1, exact cable 1): they were removed
  (one reason was rewritten), the other 385 stamped. Scores of earlier rounds for those
  modules leaned on them; sweep, frf, models.dsm, interaction and the guard were judged
  again above; eigen, modes (part way), catenary, catenary_solve, cable.exact and the
  rest of the physics core were not.

Then an eighth round, the same seed and sample size, judged by the own test files: each
sampled mutant planted into a copy of the package (today's source) and its module's own test
file run (P), instead of mutmut's run of every test that reaches the function. A mutant
under which the file cannot run (the conftest's default cables refused at import, or a
fixture failing) counts as killed. "first pass": that file before any new test, killed /
survived (among the survivors, mutants named equivalent before); "after": killed / left /
equivalent, once each survivor was killed by a new test of the own file (planted), named
equivalent (stamped, its diff checked against its reason) or left. First, the partial
samples of earlier rounds, all 100 judged anew:
=================================  ======  ===========  ==========================  ======
module (mutants in all)            judged  first pass   after: killed/left/equiv.   score
=================================  ======  ===========  ==========================  ======
params (109)                       100     97 / 3       100 / 0 / 0                 100 %
_validate (209)                    100     87 / 13      98 / 0 / 2                  100 %
report.robot (543)                 100     89 / 11      97 / 0 / 3                  100 %
cli.workspace (513)                100     74 / 26      96 / 0 / 4                  100 %
robot.statics (813)                100     78 / 22      86 / 1 / 13                 98.9 %
report.geometry3d (539)            100     81 / 19      98 / 0 / 2                  100 %
=================================  ======  ===========  ==========================  ======

  params: 61 of its kills are the conftest failing at import (a default Cable or Damping
  refused, or a TypeError), each checked to come from the mutant. report.geometry3d had no
  test file of its own: its first pass ran test_report_robot3d.py, where its tests were,
  and the new test_report_geometry3d.py kills its survivors. robot.statics' first pass ran
  test_robot_statics.py alone; its survivors were then planted against its three files
  (the numpy loop's, and the new one of the fixed point's steps).

Then the modules edited since their rows: the mutants of the same 100-sample that lie in a
function whose code, docstrings left out, changed after the commit of the module's row,
judged the same way ("judged": how many of the module's sample lie in those functions).
=================================  ======  ===========  ==========================  ======
module (mutants in all)            judged  first pass   after: killed/left/equiv.   score
=================================  ======  ===========  ==========================  ======
analyses.calibrate (843)           84      75 / 9       80 / 0 / 4                  100 %
analyses.checks (442)              28      20 / 8       28 / 0 / 0                  100 %
analyses.compare_lumped (319)      100     90 / 10      98 / 0 / 2                  100 %
analyses.damped (296)              83      74 / 9       75 / 3 / 5                  96.2 %
analyses.eigen (828)               36      27 / 9       33 / 0 / 3                  100 %
analyses.eigen_matrix (397)        12      7 / 5        12 / 0 / 0                  100 %
analyses.frf (430)                 27      27 / 0       27 / 0 / 0                  100 %
analyses.interaction (167)         50      44 / 6       48 / 0 / 2                  100 %
analyses.measured (571)            28      21 / 7       26 / 0 / 2                  100 %
analyses.measured_frf (392)        48      42 / 6       44 / 0 / 4                  100 %
analyses.modes (328)               15      10 / 5       15 / 0 / 0                  100 %
analyses.optimal_tensions (872)    6       5 / 1        6 / 0 / 0                   100 %
analyses.participation (364)       26      15 / 11      21 / 0 / 5                  100 %
analyses.platform_modes (275)      61      47 / 14      61 / 0 / 0                  100 %
analyses.recommend (500)           28      27 / 1       28 / 0 / 0                  100 %
analyses.sensitivity (923)         31      29 / 2       29 / 0 / 2                  100 %
analyses.settings (381)            63      56 / 7       60 / 0 / 3                  100 %
analyses.sweep (612)               19      19 / 0       19 / 0 / 0                  100 %
analyses.uncertainty (754)         46      38 / 8       43 / 0 / 3                  100 %
cable.catenary (633)               22      19 / 3       20 / 0 / 2                  100 %
cli.analysis (811)                 25      22 / 3       25 / 0 / 0                  100 %
cli.common (563)                   26      23 / 3       26 / 0 / 0                  100 %
cli.report (210)                   26      24 / 2       24 / 0 / 2                  100 %
cli.simulate (565)                 98      92 / 6       96 / 0 / 2                  100 %
cli.sweep (573)                    81      76 / 5       77 / 1 / 3                  98.7 %
io.table (102)                     62      57 / 5       57 / 0 / 5                  100 %
maps.workspace (768)               42      35 / 7       42 / 0 / 0                  100 %
models.dsm (618)                   33      32 / 1       33 / 0 / 0                  100 %
models.dsm_guard (265)             41      38 / 3       40 / 0 / 1                  100 %
models.exact (413)                 22      20 / 2       20 / 0 / 2                  100 %
plot.accuracy (360)                83      72 / 11      83 / 0 / 0                  100 %
plot.frf (348)                     98      91 / 7       96 / 0 / 2                  100 %
plot.modes (648)                   35      28 / 7       33 / 0 / 2                  100 %
plot.sweep (276)                   89      83 / 6       85 / 0 / 4                  100 %
plot.workspace (681)               45      39 / 6       44 / 0 / 1                  100 %
robot.waypoints (544)              30      29 / 1       29 / 0 / 1                  100 %
scenes.caspr (286)                 21      19 / 2       21 / 0 / 0                  100 %
timedomain.dynamics (849)          3       3 / 0        3 / 0 / 0                   100 %
=================================  ======  ===========  ==========================  ======

  Found on the way and fixed, each with a test that fails on the old code: the
  Wittrick-Williams search asked for more modes than a discrete rung's DOFs doubled its band
  to the 1e8 rad/s cap and raised ConvergenceError (the matrix method refused it; both do
  now, naming n_modes); compare_modes named a refused weight's eigenvalues rounded to 6
  decimals, so that -4e-7 read -0.0 (now 4 significant digits). What the survivors showed
  untested, now documented where it was not and tested: design_checks with stated
  uncertainties, the platform modes' band growth and its ceiling, modal_data's paths, the
  massless modes' values, the seed grid, cable_fields' frequency, the calibration's
  refusals and infinite bounds, the workspace map's interruption and Dask client, the
  report's printed lines and files, the views' properties. eigen._illinois mutmut_143 is
  killed (a root on the bracket's end, f_lo = 0, gave a RuntimeWarning) and _31 named
  equivalent with its own reason. The 61 equivalents whose function changed after their
  judgement (the stamps said so) were checked against the code they were stamped with: 30
  moved to the number their mutation has now, 23 kept, 8 dropped (calibrate mutmut_537
  raises TypeError; exact_mesh 15, 17, 51 and 76 are killed by the mesh's spacing test,
  which moved into the mesh's own file; dsm_guard mutmut_25's einsum is gone; two landed
  on keys already judged). Left: robot.statics' _step_distribution mutmut_35 (as in the
  seventh round; measured since: the same lengths and the same kinds of error at 960 poses
  of CoGiRo and three rising-cable robots, on both loops, but an error's text may differ);
  damped mutmut_147 and _54 (as in the second round) and _110 (the errstate around K at a
  secant iterate: it matters where K overflows there, which no test robot's secant
  reaches; the NaN return covers it); cli.sweep's mutmut_266 (the legend's "best"
  place, as in the third round). analyses.measured_frf has no test file of its own: its
  tests are in test_analyses_measured.py, which is its row's file.

  Coverage after the eighth round: every module with mutants has a row, and no row is a
  partial sample. Rows of earlier rounds hold for the functions not edited since; the
  functions edited since have the rows above. The two functions this round's fixes edited
  were then judged again on their new source, the same way: eigenfrequencies' 17 sampled
  mutants (16 killed, 1 equivalent) and compare_modes' 100 (91 killed, then 93 with a test
  of a text weight's message; 7 equivalent: einsum subscripts twice, += on an empty list,
  an empty assignment, an inclusive comparison, a clip that cannot bind, 1e+300; some of
  them argued but not named in the second round).

  Then the eighth round's five survivors left were killed or named, each planted against its
  module's own files:
  - damped_modes mutmut_54 (the secant's disc, 0.2 |estimate|: an estimate moved to 0.85
    of itself still finds the root, to 0.75 gives NaN), _110 (a model whose K overflows in an
    intermediate at complex omega: no warning leaves) and _147 (a triple root on a synthetic
    Jordan-coupled K: the copy whose search found it again keeps it) are killed; the
    docstring now states the disc, the silenced warnings, where a multiple root found again
    goes, and that a lone mode (n_modes=1) keeps any root its secant converges to in its disc.
  - robot.statics _step_distribution mutmut_35 is killed by a heavy rising cable whose
    straight chords fit no distribution: its relaxed lower limit 1e-3 t_min - lo went below
    zero ("tension must be > 0"). The search for that pose found an error of the real code:
    a relaxed start that asked a cable less than any catenary between its ends has at the
    platform was taken as the pose's refusal, with the remedy "raise t_min to above about
    76.47 N" where the pose holds only for t_min up to 49.07 N. The start now takes that
    cable's catenary of least tension there (theory.md §4); on 600 random four-cable robots
    with a rising cable, 63 refusals changed their message to the limits' or the
    workspace's, and none changed kind or became a solution.
  - cli.sweep mutmut_266 is named equivalent (the legend's 'best' place is upper left at
    the anchor: the last waypoint's line crosses the other candidate).
  The functions the statics fix edited were judged again on the new source: the module's
  100-sample (drawn again, as its count moved from 813 to 855 mutants) holds 22 mutants of
  _fixed_point and _start_or_request, and all 34 of the new _start_or_request were judged:
  52 in all, 45 killed at once, 3 killed by two new tests of the loop's exit rule (FAST's
  slow contraction, whose margins enter relative to the largest tension; a planted toggle
  that stalls the loop below and above 1e-9) and 1 by the relaxed start's remedy under
  another gravity with the same weights; _fixed_point mutmut_153 and _start_or_request
  mutmut_22 and _34 are named equivalent. A last guard (a least end tension not found,
  inf, leaves the start to the diagnosis, with a test) edited _start_or_request again, and
  it was judged once more with the module's sample drawn again (857 mutants): its 36
  mutants and the sample's 23 in the two functions, 55 in all: 52 killed at once, 1 more
  (since_best > 10) by the stall test, which now replays the exit rule from the iterates,
  and the two equivalents, renumbered to mutmut_24 and _36. With these, no survivor of
  either table is left: robot.statics 87 / 0 / 13 of the eighth round's sample,
  analyses.damped 78 / 0 / 5 and cli.sweep 77 / 0 / 4, each 100 %.
  Then the counts of reprs and messages were put in the singular for one (dynstiff._text, a
  new module), which edited eleven reprs, import-caspr's command and Robot.__post_init__.
  Their sampled mutants and all 4 of _text were judged on the new source, each against its
  module's own file: 160 in all (Robot.__post_init__'s 42 of the module's 100-sample, drawn
  again after its last edit), 151 killed at once (19 of them as the conftest's robots were
  refused at import), and the 9 survivors killed by new tests of the reprs' counts and of
  Robot's whole messages. Robot.__post_init__ mutmut_49, an equivalent, was re-stamped after
  its diff was checked.
  Then the slow tier's scene-file fuzzer (EA = 7.9e-308) found unstretched_length_for_tension
  refusing with a value nobody gave ("unstretched_length must be > 0, got 0.0"), and the
  search around it a silently wrong tension (600 N for 300 at EA = 1e-300: Brent's step
  tolerance was on the chord's scale). Fixed (the tolerance on L0's scale, a strain beyond
  the float range refused naming the tension, a residual check on the tension found); the
  function's 35 mutants in the module's sample (drawn again, 545 mutants) were judged on
  the new source against test_cable_catenary_solve.py: 27 killed at once, 3 more by new
  tests (a sagging root beyond the chord, a trial length whose catenary does not converge),
  5 equivalent (8 of the function's equivalents renumbered by their diffs and 2 re-stamped;
  2 new: the short end shrunk by 0.75 whatever EA, and the search giving up one trial
  earlier). 732 equivalents, none stale.

Then a ninth round, after dynstiff.modes' cable energies were batched over the modes and
cables (cable.dsm _fields and field_kinetic_energies new, cable_field and
cable_kinetic_energy through them, all four then moved to cable.dsm_fields; the models'
cable_kinetic_energies; modes and _energy_basis), the sensitivities' assembly batched
(sensitivity: _checked_request, _null_vectors, _assemble, sensitivities_at,
frequency_sensitivities; SensitivityResult moved to sensitivity_result; the component cross
product in six functions of the kernels, rungs, statics and lumped modules) and
damped_modes' attribution fixed. Every mutant of an edited
function in its module's 100-sample (drawn again on the final source) was planted, each
against its module's own test files (cable.dsm with test_models_dsm.py, modes with the
participation and sensitivity files, which call it): 444 on the first source, then the 63
the sensitivity module's new sample added or the first pass left, then damped_modes' 59
(its sample of 62 less 3 equivalents).
- First pass: 412 of 439 killed at once. The survivors and what became of them:
  - killed by new tests: modes mutmut_97 and _120 (every root taken as on a pole; FAST's
    4th and 6th roots, 3.3e-9 from the first pole of all six cables with a null eigenvalue
    of 3e-4 of the scale, moving their platform: shares against the total modal mass);
    _null_vectors _64 and _86 (the pole rule's threshold: a pole planted at a root, the null
    eigenvalue at 0.5 and 2 times 1e-6 of the scale, in modes and in the sensitivities);
    frequency_sensitivities _5 (a rung without sensitivities: the whole message); the
    tornado chart's _1, _31, _33, _40, _48, _49, _55, _57, _67 (its docstring now states
    the order, the colours, the zero line; the test reads the bars); _assemble _86 and _93
    of the new source (a cluster's d zeta against the damped roots of the octahedron, which
    found damped_modes' error below); sensitivity_lumped forms _8 and _98, the two left
    "not handled" in the fourth round (the gravity vector's x component changed the
    lumped rung's mass, centre-of-mass and rotation sensitivities by 4 to 7 %: a test
    against central differences; EA / axial flips the loss factor's d zeta: a test against
    the closed form's, converging with the segments);
  - removed: _assemble's lone-root branch inside the cluster loop (mutmut_78 of the first
    source), unreachable once lone roots are assembled at once;
  - named equivalent: 12 (below, with their reasons), and modes _84 joining _78 and _92;
  - _assemble _66 of the first source (a cluster's lambda from its second root, 1e-8 from
    the first at most) is not in the final source's sample, and was not judged again.
- Stale equivalents: 16 on the first source. modes _energy_basis 29 and 31 (the
  polarisation loop, now one batched call) and sensitivities_at 43 (the second expansion
  of the parameters, gone) were dropped; sensitivities_at 95, 109, 110 renumbered to 82,
  96, 97 after their diffs were checked; the other 10 (modes 21, 62, 78, 92; lumped forms
  122, 233, residual 49; FrequencyModel.__init__ 77, 97, 132) and damped_modes 2, 36, 38,
  153 keep their numbers, their diffs and reasons checked against the new code, and were
  re-stamped.
- damped_modes (its attribution fixed): 59 planted against test_analyses_damped.py, 54
  killed, 5 named equivalent (three moves of the secant's second start, two inclusive
  comparisons at exact ties). 747 equivalents.

Earlier, the physics core only (2 children; the sample was then drawn with one generator
over the core's modules, so today's per-module samples are other mutants):
- ``--sample 200``: 2382 mutants (chord has 182 in all), 2193 killed, 1 survived, 188
  equivalent: 99.95 %; every module's 95 % interval starts at 97.1 % or above. About 2.5 h
  of wall time in all, the rechecks after new tests included.
- Every mutant of chord (182), platform (393), exact_model (410), frf (330) and assembly
  (650): 100 % each but assembly, 99.8 %; the last four modules took 7 to 20 min each.
- Per mutant, the tests alone take 0.8 s when they kill it, 13 s when it survives (every
  test reaching it runs) and 3.5 min when it hangs to its timeout; the throughput was 11 to
  57 mutants a minute. The whole core, 9251 mutants, is some 5 to 10 h on this machine.
"""

import argparse
import collections
import os
import re
import subprocess
import sys
import time
import zlib

import numpy as np

#: Mutants with no observable effect, with the reason (mutant name -> why).
EQUIVALENT = {
    "dynstiff.cable.chord.xǁChordParametersǁpsi__mutmut_3":
        "complex branch for an undamped cable: the same psi with a zero imaginary part",
    "dynstiff.cable.chord.xǁChordParametersǁpsi__mutmut_13":
        "c >= 0 instead of c > 0: the complex branch again, same values",
    "dynstiff.cable.chord.x_chord_parameters__mutmut_23":
        "gp >= instead of gp >: differs only when gp equals the threshold exactly",
    "dynstiff.cable.chord.x_chord_parameters__mutmut_24":
        "threshold 1e-12/g instead of 1e-12 g: both far below any non-vertical chord's gp",
    "dynstiff.cable.chord.x_chord_parameters__mutmut_30":
        "max(g, 1) instead of max(g, 1e-300): differs only for 0 < g < 1 m/s^2 and gp tiny",
    "dynstiff.cable.chord.x_chord_parameters__mutmut_49":
        "cos_theta >= instead of >: differs only at cos_theta = 1e-12 exactly",
}
_FRF_FILTER = ("the pre-filter of the pole averaging (frf.py): a changed threshold moves only "
               "frequencies whose K is between ~1e6 and ~1e8 times its regular size, where "
               "the plain LU's error is below 1e-8 relative (6e-2 at the pole itself, where "
               "every variant still averages)")
_FRF_FAST = ("the compiled kernels switched off: the numpy path gives the same H to a few eps "
             "x cond K (test_numpy_fallback_equals_the_compiled_path)")
_FLOAT = "dtype=float dropped on an array that is already float64"
EQUIVALENT.update({f"dynstiff.analyses.frf.x_frf__mutmut_{n}": _FRF_FILTER
                   for n in (48, 49, 50, 54, 56, 58, 61, 62, 63)})
EQUIVALENT.update({f"dynstiff.analyses.frf.x__receptance__mutmut_{n}": _FRF_FAST
                   for n in (1, 5, 32)})
EQUIVALENT.update({f"dynstiff.analyses.frf.x__solve__mutmut_{n}": _FLOAT for n in (15, 17)})
_RESULT_TYPE = ("one of the four entries dropped from np.result_type: any damping makes at "
                "least two of them complex (planted and checked), so the dtype is unchanged")
EQUIVALENT.update({f"dynstiff.cable.dsm.x_{f}__mutmut_{n}": _RESULT_TYPE
                   for f in ("local_end_stiffness", "local_two_end_stiffness")
                   for n in range(15, 23)})
_EINSUM = "upper-case einsum subscripts: the same contraction"
_MESH = ("the sampling of the mesh measure Phi (theory.md §11.2): the extra points of the "
         "asinh grading, their clipping to [0, L0], a floor of 1 N under T, or the last but "
         "one sample deciding the element count change the edges by less than the 4e-7 of "
         "the 4001-point sums (test_elements_are_spread_evenly_in_the_mesh_measure)")
EQUIVALENT.update({f"dynstiff.cable.exact_mesh.x_mesh__mutmut_{n}": _MESH
                   for n in (12, 34, 38, 39, 63, 110)})
_CE = "dynstiff.cable.exact."
# ExactCable.__init__, _build_modes and _self_check were rewritten for the mixed form
# (theory.md §11.2): their equivalent mutants are to be judged again.
EQUIVALENT.update({
    "dynstiff.cable.exact_mesh.x_static_along__mutmut_7": _FLOAT,
    "dynstiff.cable.exact_mesh.x_static_along__mutmut_9": _FLOAT,
    f"{_CE}xǁExactCableǁdynamic_stiffness__mutmut_24": "reshape(-2, ...) infers like -1",
    f"{_CE}xǁExactCableǁbeta_dyads__mutmut_1": "default ends changed: any value but 'both' "
                                               "gives the end block",
    f"{_CE}xǁExactCableǁbeta_dyads__mutmut_2": "default ends changed: any value but 'both' "
                                               "gives the end block",
    f"{_CE}xǁExactCableǁbeta_dyads__mutmut_19": _EINSUM,
    f"{_CE}xǁExactCableǁ_check__mutmut_4":
        "> or >= omega_max (1 + 1e-12): differs only at exactly that float",
    f"{_CE}xǁExactCableǁmode_count__mutmut_7": "side='left' is searchsorted's default",
    f"{_CE}xǁExactCableǁend_response__mutmut_6":
        "complex(omega) for real omega: the same w^2 with a zero imaginary part, and the "
        "response is complex anyway",
})
EQUIVALENT.update({
    "dynstiff.analyses.eigen.x__search__mutmut_35":
        "a bracket never counted as isolated is bisected on the count to rtol instead of "
        "refined by regula falsi: the same roots, more counts",
})
EQUIVALENT.update({
    "dynstiff.models.dsm.xǁFrequencyModelǁundamped__mutmut_3":
        "every warning ignored while the undamped copy is built, not only the "
        "ClosedFormWarning that the original already issued: no other warning arises there",
    "dynstiff.models.dsm.xǁFrequencyModelǁundamped__mutmut_5":
        "every warning ignored while the undamped copy is built, not only the "
        "ClosedFormWarning that the original already issued: no other warning arises there",
    "dynstiff.cable.catenary_solve.x_unstretched_length_for_tension__mutmut_119":
        "k >= 200 instead of > 200 in a bracket expansion that ends after a few steps",
})
_START = ("the starting guess of the chain's Newton (its tension estimate or force-space "
          "start): the equilibrium it converges to, checked by its residual, is the same")
EQUIVALENT.update({f"dynstiff.cable.lumped_chain.x__tension_estimate__mutmut_{n}": _START
                   for n in (25, 29, 48, 77)})
EQUIVALENT.update({f"dynstiff.cable.lumped_chain.x__force_space_start__mutmut_{n}": _START
                   for n in (28, 178, 184)})
EQUIVALENT.update({
    "dynstiff.cable.lumped_chain.x__slack_segment__mutmut_30":
        "the stretch term of the hanging lengths (w/EA ~ 1e-5 of l0) moves the gap of the "
        "slack test far less than l0, so the same segment is found",
    "dynstiff.cable.lumped_elements.x_potential_energy__mutmut_22":
        "the merit function of the chain Newton's line search (1.5 instead of 0.5 EA l0 "
        "strain^2): a step is accepted a little differently, the equilibrium is the same",
    "dynstiff.cable.lumped_chain.x__newton__mutmut_77":
        "the iteration count reported when Newton did not converge: max_iter + 2 instead of + 1 "
        "is still above max_iter, which is what the caller tests",
})
EQUIVALENT.update({
    "dynstiff.cable.guard.xǁClosedFormValidityǁreasons__mutmut_23":
        "e >= rtol instead of e > rtol: differs only at exactly rtol",
    "dynstiff.cable.psi.x_mode_count_psi__mutmut_11":
        "c / (+-1) equals c * (+-1)",
    "dynstiff.cable.catenary_solve.x__initial_guesses__mutmut_29":
        "one of the catenary Newton's starting guesses: the solution it converges to, "
        "checked by its residual, is the same",
    "dynstiff.models.exact.xǁExactModelǁ__init____mutmut_97":
        "the dtype of the zeros the static parts are summed into: const = const + K_s "
        "upcasts to complex anyway",
    "dynstiff.robot.platform.x_quaternion_to_rotvec__mutmut_37":
        "the theta^4 coefficient of the small-angle series (theta <= 1e-3): 1/2880 of "
        "theta^4 is below 2e-16 of the leading term",
})
_COST = ("the regula falsi's step rule (second point, Anderson-Bjorck factor, halving rule "
         "or stopping width): every bracket still closes on the same root to rtol, only the "
         "number of evaluations changes (the root's value is tested, its cost bounded on "
         "smooth and curved functions)")
EQUIVALENT.update({f"dynstiff.analyses.eigen.x__illinois__mutmut_{n}": _COST
                   for n in (22, 86, 155, 179, 202, 314)})
EQUIVALENT["dynstiff.analyses.eigen.x__illinois__mutmut_31"] = (
    "invalid='ignore' dropped around the regula falsi point: the bracket keeps f_lo >= 0 > "
    "f_hi, both finite, so FH - FL < 0: no 0/0, inf/inf or inf - inf (a NaN is quiet)")
EQUIVALENT.update({
    "dynstiff.analyses.eigen.x__illinois__mutmut_11": "the side flags as floats: compared with +-1 "
                                             "all the same",
    "dynstiff.analyses.eigen.x__real_symmetric__mutmut_3": "K.real of a real K is K",
})
EQUIVALENT.update({
    "dynstiff.cable.catenary.x__mean_tension__mutmut_11":
        "the sign of V0 / (V0 + W) is the sign of V0 (V0 + W)",
    "dynstiff.cable.catenary_solve.x__initial_guesses__mutmut_36":
        "a starting-guess branch boundary (lh <= or < 1e-6 L): the solution is the same",
    "dynstiff.cable.catenary_solve.x__initial_guesses__mutmut_76":
        "V0's starting guess 3 times larger (1.5 w0 instead of 0.5 w0): the equilibrium for "
        "given L0 and ends is unique and checked by its residual, and the other guesses are "
        "tried too",
    "dynstiff.cable.catenary.x_end_stiffnesses__mutmut_38":
        "the placeholder H of cables outside the taut mask, whose results are discarded",
    "dynstiff.cable.catenary_solve.x_unstretched_length_for_tension__mutmut_52":
        "the start of the bracket on L0, which is widened until it brackets the tension",
    "dynstiff.cable.catenary_solve.x_unstretched_length_for_tension__mutmut_77":
        "the short end shrunk by 0.75 per step whatever EA (1.0 * max for 1.0 / max): a "
        "wider bracket of the same taut root",
    "dynstiff.cable.catenary_solve.x_unstretched_length_for_tension__mutmut_94":
        "k counted from 1: the lower bracket's search gives up after 200 trials instead of "
        "201 (1.05^200 = 17,000 times the start, or 200 halvings)",
})
EQUIVALENT.update({
    "dynstiff.robot.platform.x_quaternion_to_rotvec__mutmut_29":
        "the sign of the theta^4 term of the small-angle series (theta <= 1e-3): below 2e-16",
    "dynstiff.robot.platform.x_rotvec_to_quaternion__mutmut_21":
        "3841 for 3840 in the theta^4 term of the small-angle series: below 1e-19",
    "dynstiff.robot.platform.x_rotvec_to_quaternion__mutmut_5": _FLOAT,
    "dynstiff.robot.platform.x_quaternion_to_rotvec__mutmut_5": _FLOAT,
    "dynstiff.robot.distribution.x__closest_in_box__mutmut_56":
        "a step tried when |p| > 1e-12 / scale instead of 1e-12 scale: every entry below "
        "1e-12 scale gets no room limit, so the step is the full one, as without the test",
    "dynstiff.robot.statics.x__end_quantities__mutmut_41":
        "the y component of the horizontal direction of an exactly vertical chord: it is "
        "multiplied by H = 0",
})
_WARM = ("the warm start of the tension distribution (the guessed active set, its feasible "
         "start, its tolerance or whether it is tried): a start is used only when it is "
         "feasible, and the active-set method then ends at the unique minimiser of the "
         "strictly convex problem, as from the LP's start (tested bitwise on random problems)")
EQUIVALENT.update({f"dynstiff.robot.distribution.x_distribution_with_active_set__mutmut_{n}": _WARM
                   for n in (45, 61, 76, 87, 89, 95, 97, 98, 103, 110)})
EQUIVALENT.update({f"dynstiff.robot.distribution.x__active_solution__mutmut_{n}": _WARM
                   for n in (2, 4, 28)})
_EM = "dynstiff.models.exact.xǁExactModelǁ"
EQUIVALENT.update({
    f"{_EM}__init____mutmut_126": _EINSUM,
    f"{_EM}__init____mutmut_85": "np.array(lever_arms) without dtype=float: the "
                                 "equilibrium's lever arms are a float array already",
    f"{_EM}__init____mutmut_133": "beta_dyads(ends=None): any value but 'both' gives the "
                                  "end block",
    f"{_EM}dynamic_stiffness__mutmut_30": "the block of frequencies evaluated at once "
                                          "(memory only; every block gives the same K)",
})
# (the errstate mutants of local_coefficients and end_response, once named equivalent here
# because "a float frequency next to a float eigenvalue does not hit w^2 mu = 1", are killed:
# such frequencies exist, test_a_response_exactly_on_a_clamped_pole_is_finite_and_silent)
_GROW = ("the first band tried for the exact clamped modes (or the loop bound, or one more "
         "mode than needed): the band grows by 1.5 until it holds n modes, and modes inside "
         "the band are exact whatever band was asked")
EQUIVALENT.update({f"dynstiff.cable.modes.x__exact_modes__mutmut_{n}": _GROW
                   for n in (2, 3, 4, 5, 6, 9, 17, 19)})
EQUIVALENT.update({
    "dynstiff.cable.dsm.x_block_coefficients__mutmut_1":
        "default blocks='end' changed: any value but 'both' gives the end block",
    "dynstiff.cable.dsm.x_block_coefficients__mutmut_2":
        "default blocks='end' changed: any value but 'both' gives the end block",
    "dynstiff.cable.dsm.x_block_coefficients__mutmut_35": "kw_s - 0 equals kw_s + 0",
    "dynstiff.cable.guard.x_guard_cable__mutmut_17":
        "error < guard_rtol instead of <=: differs only at exactly guard_rtol",
    "dynstiff.cable.guard.x_guard_cable__mutmut_26":
        "error < guard_rtol instead of <=: differs only at exactly guard_rtol",
    "dynstiff.analyses.sweep.x__mac__mutmut_3":
        "MAC is invariant to the scale of M (1.5 (Mx + My) instead of 0.5 (Mx + My))",
    "dynstiff.analyses.sweep.x__assign__mutmut_3":
        "X.shape[1] == 0 instead of X.shape[0] == 0: with no global mode the assignment "
        "of an empty MAC matrix is empty too",
    "dynstiff.analyses.sweep.x__assign__mutmut_26":
        "MAC > mac_min instead of >=: differs only at MAC exactly mac_min",
    "dynstiff.robot.distribution.x__limits__mutmut_8":
        "t_min[1] instead of t_min[0] inside the branch where all t_min are equal",
    "dynstiff.robot.distribution.x__limits__mutmut_9":
        "t_max[1] instead of t_max[0] inside the branch where all t_max are equal",
    "dynstiff.cable.catenary.xǁCatenaryStateǁtension__mutmut_3":
        "dtype=float dropped: T(s) = hypot(H, V0 + w s) is float for integer s too",
    "dynstiff.cable.catenary.xǁCatenaryStateǁtension__mutmut_5":
        "dtype=float dropped: T(s) = hypot(H, V0 + w s) is float for integer s too",
    "dynstiff.cable.catenary_solve.x__vertical_solution__mutmut_3":
        "h <= 0 instead of h < 0: a vertical chord of zero length is refused before",
    "dynstiff.cable.catenary_solve.x__vertical_solution__mutmut_13":
        "> 0 instead of >= 0 at the slack boundary: differs only when V0 + W is exactly 0",
    "dynstiff.cable.catenary_solve.x__vertical_solution__mutmut_24":
        "< 0 instead of <= 0 at the slack boundary: differs only when V0 is exactly 0",
    "dynstiff.cable.dsm.x__real_if_undamped__mutmut_4":
        "the kernels are already real for an undamped cable at real omega: np.real is a no-op",
    "dynstiff.cable.dsm.x_cable_dynamic_stiffness__mutmut_79":
        "omega is real here (complex omega is refused by the validation)",
    "dynstiff.cable.dsm.x_cable_dynamic_stiffness__mutmut_154":
        "omega is real here (complex omega is refused by the validation)",
    "dynstiff.cable.dsm.x_cable_dynamic_stiffness__mutmut_29":
        "the exact cable's band floored at 1 rad/s: modes inside any band are exact",
    "dynstiff.cable.dsm.x_lowest_string_omega__mutmut_1":
        "the floor of the exact cable's band only: results inside any band are exact",
    "dynstiff.cable.dsm.x_lowest_string_omega__mutmut_2":
        "the floor of the exact cable's band only: results inside any band are exact",
    "dynstiff.cable.dsm.x_lowest_string_omega__mutmut_4":
        "the floor of the exact cable's band only: results inside any band are exact",
})
EQUIVALENT.update({"dynstiff.analyses.sweep.x__mac__mutmut_16": _EINSUM,
                   "dynstiff.analyses.sweep.x__mac__mutmut_27": _EINSUM})
EQUIVALENT.update({
    "dynstiff.analyses.interaction.x__check_modes__mutmut_3":
        "dtype=float dropped on frequencies that are float already (ModalResult)",
    "dynstiff.analyses.interaction.x__check_modes__mutmut_5":
        "dtype=float dropped on frequencies that are float already (ModalResult)",
    "dynstiff.analyses.frf.x__solve__mutmut_31":
        "the batched solve given None raises LinAlgError, so every frequency goes through the "
        "per-frequency fallback, which gives the same H",
})
EQUIVALENT.update({f"dynstiff.analyses.interaction.x_to_frame__mutmut_{n}":
                   "dtype=float dropped on a list of Python floats (float64 even when empty)"
                   for n in (23, 25, 30, 32, 36, 38)})
EQUIVALENT.update({
    "dynstiff.analyses.frf.x_channel_maps__mutmut_42":
        "np.eye(7) instead of np.eye(6) indexed by DOF numbers < 6: the same entries",
    "dynstiff.analyses.frf.x_channel_maps__mutmut_78":
        "np.moveaxis(mat, 0, +1) equals np.moveaxis(mat, 0, -1) on a 2-D matrix",
    "dynstiff.analyses.frf.x_frf__mutmut_46":
        "stacklevel=3 of the PoleWarning: under mutation the trampoline adds a frame, so the "
        "test of the caller's file cannot tell 2 from 3 (stacklevel 1 is killed)",
    "dynstiff.models.dsm.xǁFrequencyModelǁdynamic_stiffness_and_count__mutmut_2":
        "the fused kernel skipped for every model: K and J0 from the two separate calls, "
        "equal to 1e-13 (test_with_damping_keeps_the_options_and_the_fused_kernel_...)",
    "dynstiff.models.dsm.xǁFrequencyModelǁdynamic_stiffness_and_count__mutmut_3":
        "the fused kernel skipped for the base class: the same K and J0 from two calls",
    "dynstiff.models.dsm.xǁFrequencyModelǁdynamic_stiffness_and_count__mutmut_33":
        "reshape(n, -2) equals reshape(n, -1) (any negative size is inferred)",
    "dynstiff.analyses.interaction.xǁProximityWarningǁ__hash____mutmut_1":
        "a constant hash keeps set and dict semantics (equality decides); only slower",
    "dynstiff.analyses.sweep.xǁSweepResultǁto_frame__mutmut_3":
        "pd.array of an int64 array infers Int64 without being told",
    "dynstiff.analyses.sweep.xǁSweepResultǁto_frame__mutmut_5":
        "pd.array of an int64 array infers Int64 without being told",
    "dynstiff.analyses.sweep.xǁSweepResultǁto_frame__mutmut_9":
        "None assigned into an Int64 array is <NA>, like pd.NA",
})
_FIRST_BAND = ("the growth of the band of the exact clamped modes and its failure message: "
               "never reached, the first band (1.2 (n + 1) times the lowest string "
               "frequency) holds 2.5 to 3.3 times the n modes asked on every hard test cable "
               "(n = 1, 3, 10)")
_CAT_START = ("the starting guesses of the elastic catenary's Newton: the equilibrium for "
              "given L0 and ends is unique and checked by its residual, and two starts are "
              "tried")
_BOUNDARY = "a strict comparison made inclusive: differs only at exactly equal floats"
_ALL_CHORDS = ("the vertical test against 1e-14 of the norm of all chords instead of each "
               "one: differs only for a chord between 1e-14 of its own length and of all "
               "lengths from vertical")
_STRAIGHT = ("each iteration's catenaries started from straight cables instead of the "
             "previous iteration's: the same (unique, residual-checked) catenaries, more "
             "Newton steps")
_ARMS_WRITTEN = "dtype dropped on lever arms written into a float array: the same maps"
_FALSY = "None given where False is meant: falsy all the same"
_REMEASURE = ("which cables the guard measures against the exact cable: one already said, "
              "already measured within guard_rtol, or estimated within it is measured again "
              "(time only: a cable is said once, and a measured error never exceeds the "
              "estimate on the 150 cables of theory.md §11.5)")
_CONST = ("the dtype of the zeros the cables' static stiffnesses are summed into: the sum "
          "const + ... upcasts to complex where a cable is damped, and K.real follows for "
          "an undamped model")
_ZERO_FORCE = ("never reached: the chord direction filled in where a start segment's force is "
               "exactly zero, which needs a vertical chain whose force at A cancels a whole "
               "number of segment weights")
_VERTICAL = ("the horizontal direction of an exactly vertical chord in the batched end "
             "stiffness: such a cable has H = 0 and takes its state's own end stiffness")
EQUIVALENT.update({
    "dynstiff.models.dsm_guard.x_warn_once__mutmut_7":
        "not observable under mutmut: stacklevel dropped, killed in the normal run by "
        "test_guard_warnings_point_at_the_callers_line_and_name_the_slack_cable (planted "
        "and checked), but mutmut's own frames move every warning's place",
    "dynstiff.cable.psi.x_mode_count_psi__mutmut_24":
        "-2 instead of -1 in a factor whose sign alone is tested",
    "dynstiff.cable.psi.x_check_frequency_range__mutmut_39":
        "omega as a column for a single cable too: psi is elementwise, the same maximum",
    "dynstiff.cable.guard.x_guard_cable__mutmut_55":
        "cable=None dropped: None is the warning's default",
    "dynstiff.cable.modes.x__exact_modes__mutmut_22": _FIRST_BAND,
    "dynstiff.cable.modes.x__exact_modes__mutmut_24": _FIRST_BAND,
    "dynstiff.cable.catenary.x_end_stiffnesses__mutmut_77": _BOUNDARY,
    "dynstiff.cable.catenary.x_end_stiffnesses__mutmut_83": _ALL_CHORDS,
    "dynstiff.cable.catenary_solve.x__initial_guesses__mutmut_73": _CAT_START,
    "dynstiff.cable.catenary_solve.x__initial_guesses__mutmut_80": _CAT_START,
    "dynstiff.analyses.eigen.x__search__mutmut_43": _BOUNDARY,
    "dynstiff.analyses.eigen.x__illinois__mutmut_44":
        "x outside (L, H) no longer sent to bisection: the regula falsi point is a convex "
        "combination of L and H, on an end only where f is 0 there (then the bracket "
        "closes) or by rounding; a stalled bracket is still bisected after 3 steps",
    "dynstiff.analyses.eigen.x__illinois__mutmut_247":
        "the high end not moved to the second point when the pair brackets the root: the "
        "bracket closes to rtol in a few more steps, at the same root",
    "dynstiff.models.exact.xǁExactModelǁ_block__mutmut_20":
        "the viscous form of w^2 for an undamped model: its viscous rates are 0 and K.real "
        "follows (complex rounding: 1e-16; on an exact pole NaN entries for inf, both the "
        "documented 'not finite')",
    "dynstiff.models.exact.xǁExactModelǁ_block__mutmut_29":
        "division by 1 + i 0 (loss factor 0): the same values, K.real follows when undamped "
        "(complex rounding: 1e-16; on an exact pole NaN entries for inf, both 'not finite')",
    "dynstiff.cable.lumped_elements.x_block_tridiagonal_entries__mutmut_9":
        "meshgrid's 'xy' indexing transposes each element block: element stiffnesses are "
        "symmetric",
    "dynstiff.cable.lumped_chain.x__force_space_start__mutmut_101": _START,
    "dynstiff.cable.lumped_elements.x_update_segments__mutmut_27":
        "the |dd|^2 term of the length change summed over all segments: Newton's steps "
        "from the force-space start are so small that their squares do not reach the "
        "strain (segment lengths equal the node distances to 7e-15 either way, planted "
        "and checked)",
    "dynstiff.cable.lumped_chain.x__slack_segment__mutmut_23":
        "the stretch term of the hanging lengths (w/EA ~ 1e-5 of l0) moves the gap of the "
        "slack test far less than l0, so the same segment is found",
    "dynstiff.cable.lumped_elements.x_potential_energy__mutmut_20":
        "the line search's merit (energy) with EA / l0 instead of EA l0: a step is also "
        "accepted when it lowers the force residual, and the equilibrium is checked by "
        "that residual",
    "dynstiff.robot.platform.x_quaternion_to_rotvec__mutmut_3":
        "dtype=None on a quaternion: integer input gives the same float result",
    "dynstiff.robot.platform.x_quaternion_to_rotvec__mutmut_38":
        "2881 for 2880 in the theta^4 term of the small-angle series (theta <= 1e-3): below "
        "1e-18",
    "dynstiff.cable.catenary_solve.x_unstretched_length_for_tension__mutmut_138":
        "brentq's maxiter 201 instead of 200",
    "dynstiff.cable.catenary_solve.x_unstretched_length_for_tension__mutmut_53":
        "the short end of the bracket on L0 far shorter (T EA instead of T / EA): still "
        "above the target tension, the same root in more Brent steps",
    "dynstiff.cable.catenary_solve.x_unstretched_length_for_tension__mutmut_133":
        "brentq's rtol left at its default 4 eps instead of 1e-15 (4.4 eps): the same root "
        "to a few ulps",
    "dynstiff.cable.catenary_solve.x_unstretched_length_for_tension__mutmut_91":
        "the start of the lower bracket on L0, which is grown (or bisected back from slack) "
        "until the tension is under the target",
    "dynstiff.cable.catenary_solve.x_unstretched_length_for_tension__mutmut_111":
        "the lower bracket grown by 2.05 instead of 1.05 per step: the taut solution and "
        "the deep loop's are far apart in L0, and a slack trial is bisected back",
    "dynstiff.cable.catenary_solve.x_unstretched_length_for_tension__mutmut_118":
        "the bracket search gives up after 100 instead of 200 steps (1.05^100 = 130 chord "
        "lengths, or 100 halvings)",
    "dynstiff.cable.catenary_solve.x_unstretched_length_for_tension__mutmut_102": _BOUNDARY,
    "dynstiff.cable.catenary_solve.x__initial_guesses__mutmut_37": _CAT_START,
    "dynstiff.cable.catenary_solve.x__initial_guesses__mutmut_40": _CAT_START,
    "dynstiff.cable.catenary_solve.x__initial_guesses__mutmut_74": _CAT_START,
    "dynstiff.cable.catenary_solve.x__initial_guesses__mutmut_77": _CAT_START,
    "dynstiff.cable.catenary_solve.x__initial_guesses__mutmut_81": _CAT_START,
    "dynstiff.cable.catenary.x_end_stiffnesses__mutmut_81": _ALL_CHORDS,
    "dynstiff.cable.catenary.x_end_stiffnesses__mutmut_92": _VERTICAL,
    "dynstiff.cable.catenary.x_end_stiffnesses__mutmut_98": _VERTICAL,
    "dynstiff.cable.catenary.x__mean_tension__mutmut_13":
        "V0 (V0 + W) > 0 instead of >= 0: where it is 0 (V0 or V0 + W zero) both forms give "
        "W / 2",
    "dynstiff.cable.catenary.x__mean_tension__mutmut_36": _BOUNDARY,
    "dynstiff.cable.catenary_solve.x__newton__mutmut_28":
        "the starting guess's residual (only) multiplied by the span scale instead of "
        "divided: a start is never converged already, and every later residual is relative "
        "(test_long_spans_converge_and_limits_are_exact)",
    "dynstiff.cable.catenary.x_divided_differences__mutmut_14":
        "a b >= 0 instead of > 0: where a or b is 0 both branches give the same quotient",
    "dynstiff.robot.distribution.x_distribution_with_active_set__mutmut_189":
        "method='highs' is linprog's default",
    "dynstiff.robot.distribution.x_distribution_with_active_set__mutmut_178":
        "1e300 written as 1e+300: the same float",
    "dynstiff.robot.distribution.x_distribution_with_active_set__mutmut_20":
        "dtype=float dropped on t_max: integer limits give the same float tensions",
    "dynstiff.robot.distribution.x_distribution_with_active_set__mutmut_99":
        "the warm active sets tried always (n = k, or warm=False): see mutmut_100; with "
        "warm=False the reference path then ends at the same unique minimiser",
    "dynstiff.robot.distribution.x_distribution_with_active_set__mutmut_101":
        "the warm active sets tried when n = k too: see mutmut_100",
    "dynstiff.robot.distribution.x_distribution_with_active_set__mutmut_109": _WARM,
    "dynstiff.robot.distribution.x_distribution_with_active_set__mutmut_111": _WARM,
    "dynstiff.robot.distribution.x_distribution_with_active_set__mutmut_118": _WARM,
    "dynstiff.robot.distribution.x__closest_in_box__mutmut_171":
        "the returned active set's sides flipped: they only seed the next iteration's "
        "distribution, whose start is used only when feasible and which ends at the unique "
        "minimiser (see _WARM)",
    "dynstiff.robot.distribution.x__closest_in_box__mutmut_22":
        "the step limit of the active-set method 10 n - 10 instead of 10 n + 10 (n >= 2 "
        "cables here): the problems met settle in far fewer steps",
    "dynstiff.robot.statics.x__end_quantities__mutmut_11": _BOUNDARY,
    "dynstiff.robot.statics.x__end_quantities__mutmut_79":
        "V0 <= 0 instead of < 0: at V0 = 0 both forms give H",
    "dynstiff.models.dsm_guard.x_guard_static__mutmut_21": _BOUNDARY,
    "dynstiff.cable.psi.x_check_frequency_range__mutmut_50": _BOUNDARY,
    "dynstiff.cable.catenary_solve.x__newton__mutmut_80": _BOUNDARY,
    "dynstiff.cable.catenary_solve.x__newton__mutmut_70":
        "the catenary Newton's line search accepts a short step only when converged: the "
        "equilibrium for given L0 and ends is unique and checked by its residual",
    "dynstiff.cable.catenary_solve.x__initial_guesses__mutmut_63": _CAT_START,
    "dynstiff.analyses.eigen.x__illinois__mutmut_49": _BOUNDARY,
    "dynstiff.analyses.eigen.x__illinois__mutmut_125": _BOUNDARY,
    "dynstiff.analyses.eigen.x__illinois__mutmut_74":
        "the paired second point always on the low side of x: the pair still brackets a "
        "root within 0.45 rtol above x, and bisection bounds the steps; the same roots",
    "dynstiff.analyses.eigen.x__illinois__mutmut_205":
        "the Anderson-Bjorck factor never applied at the low end: plain Illinois steps "
        "there, the same roots in more steps",
    **{f"dynstiff.analyses.eigen.x__illinois__mutmut_{n}": _BOUNDARY for n in (21, 166)},
    "dynstiff.analyses.eigen.x__illinois__mutmut_6": _FLOAT,
    "dynstiff.analyses.eigen.x__illinois__mutmut_1":
        "the regula falsi's step cap 201 instead of 200: its brackets close in a few dozen "
        "steps at most; the test of a bracket that does not close gives its own max_iter",
    "dynstiff.analyses.eigen.x__search__mutmut_20":
        "searchsorted's side='left' dropped: 'left' is its default",
    "dynstiff.analyses.eigen.x__counter__mutmut_33":
        "the compiled search's step cap 201 instead of 200: its brackets close in a few "
        "dozen steps at most; the cap matters only for one that does not close, and the "
        "test of that case gives its own max_iter",
    "dynstiff.analyses.eigen.x__illinois__mutmut_16":
        "the stall counter as float zeros instead of int: it counts small integers, exact "
        "in float, compared with 3",
    "dynstiff.analyses.eigen.x__illinois__mutmut_73": _BOUNDARY,
    "dynstiff.analyses.eigen.x__illinois__mutmut_241":
        "the low end's value dropped (NaN) where the pair brackets the root: that bracket is "
        "then 0.45 rtol wide, closed, and never iterated again; the root is its midpoint",
    "dynstiff.analyses.eigen.x__illinois__mutmut_78":
        "the closing pair 1.45 rtol apart instead of 0.45: it still brackets the root, which "
        "closes one step later at most (cost only; the cost tests' bounds hold)",
    **{f"dynstiff.analyses.eigen.x__illinois__mutmut_{n}":
       "divide='ignore' dropped from the secant step's errstate: FH - FL never vanishes "
       "(f_lo >= 0 > f_hi, scaled by positive factors), only invalid (inf / inf at a pole) "
       "can occur" for n in (28, 30)},
    "dynstiff.models.exact.xǁExactModelǁdynamic_stiffness__mutmut_36":
        "the frequency blocks overlapping (step 1): every frequency written with the same "
        "value again (memory and time only)",
    "dynstiff.models.exact.xǁExactModelǁ_block__mutmut_53":
        "multiplication by 1 + i 0 (loss factor 0) in a damped model: the same values",
    "dynstiff.cable.lumped_chain.x__force_space_start__mutmut_112": _START,
    "dynstiff.cable.lumped_chain.x__force_space_start__mutmut_156": _START,
    "dynstiff.cable.lumped_chain.x__tension_estimate__mutmut_26": _START,
    "dynstiff.cable.lumped_chain.x__regularised_solve__mutmut_16":
        "check_finite=None is falsy like False",
    "dynstiff.cable.lumped_chain.x__newton__mutmut_146":
        "61 halvings of the line search instead of 60",
    "dynstiff.robot.distribution.x__closest_in_box__mutmut_15":
        "the 1 N floor of the step threshold's scale: without it the threshold is 1e-12 of "
        "tensions below 1 N, still far above their rounding; the same unique minimiser",
    "dynstiff.robot.distribution.x__closest_in_box__mutmut_173":
        "-2 instead of -1 for a lower side: only the sign of a side is used",
    "dynstiff.robot.distribution.x_distribution_with_active_set__mutmut_9":
        "dtype=float dropped on t_min: integer limits give the same float tensions",
    "dynstiff.robot.distribution.x_distribution_with_active_set__mutmut_63":
        "the all-free active set as floats instead of integers: only tested with np.any",
    "dynstiff.models.dsm_guard.x_guard_static__mutmut_5":
        "the slack cause is 0 or inf: > 1 and > 0 agree",
    "dynstiff.cable.psi.x_irvine_symmetric_roots__mutmut_83":
        "brentq's rtol left at its default 4 eps instead of 1e-15 (4.4 eps): the same roots "
        "to a few ulps",
    "dynstiff.cable.psi.x_mode_count_psi__mutmut_25": _BOUNDARY,
    "dynstiff.cable.psi.x_mode_count_psi__mutmut_35": _BOUNDARY,
    "dynstiff.cable.modes.xǁCableModesǁ__repr____mutmut_4":
        "the repr of an empty mode table: never built (n_modes >= 1 is enforced)",
    "dynstiff.cable.catenary_solve.x__initial_guesses__mutmut_44": _CAT_START,
    "dynstiff.cable.catenary.x_end_stiffnesses__mutmut_104": _VERTICAL,
    "dynstiff.cable.catenary_solve.x_unstretched_length_for_tension__mutmut_78":
        "the short end of the bracket shrunk by a larger factor per step: the same root",
    "dynstiff.cable.catenary_solve.x__newton__mutmut_72": _BOUNDARY,
    "dynstiff.cable.catenary_solve.x__validate_ends__mutmut_27": _BOUNDARY,
    "dynstiff.robot.platform.x_lever_maps__mutmut_3": _ARMS_WRITTEN,
    "dynstiff.robot.platform.x_lever_maps__mutmut_5": _ARMS_WRITTEN,
    "dynstiff.robot.distribution.x_distribution_with_active_set__mutmut_1": _WARM,
    "dynstiff.cable.lumped_chain.x__force_space_start__mutmut_77":
        "never reached: the start's Newton stops early only on a zero segment force or a "
        "singular Hessian, which no chain met (it is a start: the node Newton goes on)",
    "dynstiff.cable.lumped_chain.x__force_space_start__mutmut_224": _ZERO_FORCE,
    "dynstiff.cable.lumped_chain.x__force_space_start__mutmut_228": _ZERO_FORCE,
    f"{_EM}__init____mutmut_134": "beta_dyads(ends='XXendXX'): any value but 'both' gives the "
                                  "end block",
    f"{_EM}__init____mutmut_145":
        "a zero platform damping matrix built (ratio >= 0) and added to a damped model's K: "
        "the same values",
    f"{_EM}__init____mutmut_83": "dtype dropped on lever arms that are float already",
    f"{_EM}__init____mutmut_99": _CONST,
    f"{_EM}__init____mutmut_101": _CONST,
    f"{_EM}__init____mutmut_102": _CONST,
    f"{_EM}_block__mutmut_80": "reshape(-2, ...) infers like -1",
    f"{_EM}_check__mutmut_4": _BOUNDARY,
    f"{_EM}dynamic_stiffness__mutmut_24":
        "frequency blocks of at least 2 instead of 1: every block gives the same K (memory "
        "only)",
    f"{_EM}undamped__mutmut_6": _FALSY,
    "dynstiff.robot.platform.x_quaternion_to_rotvec__mutmut_24": _BOUNDARY,
    "dynstiff.robot.platform.x_rotvec_to_quaternion__mutmut_9": _BOUNDARY,
    "dynstiff.robot.platform.x_quaternion_to_rotvec__mutmut_7":
        "q[3] <= 0 instead of < 0: at w = 0 exactly (a half turn) q and -q give the rotation "
        "vectors +-pi n of the same rotation",
    "dynstiff.robot.platform.x_rotvec_to_quaternion__mutmut_14":
        "the sign of the theta^4 term of the small-angle series (theta <= 1e-3): below 3e-16",
    "dynstiff.robot.platform.x_rotvec_to_quaternion__mutmut_3":
        "dtype=None on a rotation vector: integer input gives the same float quaternion",
    "dynstiff.models.dsm.xǁFrequencyModelǁ__init____mutmut_77": _FALSY,
    "dynstiff.models.dsm.xǁFrequencyModelǁundamped__mutmut_11": _FALSY,
    "dynstiff.robot.distribution.x__closest_in_box__mutmut_97": _BOUNDARY,
    "dynstiff.robot.distribution.x__closest_in_box__mutmut_98":
        "step room also computed for |p| between 1e-12 / scale and 1e-12 scale: a bound taken "
        "by such a rounding-level step is released by its multiplier, and the optimum of "
        "the strictly convex problem is unique",
    "dynstiff.robot.distribution.x_distribution_with_active_set__mutmut_100":
        "the warm active sets tried when n = k too: the free cables of an active set "
        "cannot balance the platform then (rank < k), so no start is found and the same "
        "error follows",
})

# Modules outside the physics core (sample of 100 per module, seed 20261202).
EQUIVALENT.update({
    "dynstiff.analyses.verdicts.x__margin_row__mutmut_34":
        "f >= lo (1 - margin) instead of >: a mode exactly at the lower end of the margin "
        "band (" + _BOUNDARY + ")",
    "dynstiff.analyses.platform_modes.x__incomplete__mutmut_5":
        "the top of a search with no completed step: unused (searched_hz is 0 then)",
    "dynstiff.analyses.checks.x_modal_model_options__mutmut_5":
        "a given fmax_hz no longer recognised: the computed one is then overridden by the "
        "given one (**model_options last), the same dict",
    "dynstiff.io.files.x_write_text__mutmut_2":
        "encoding 'UTF-8' instead of 'utf-8': codec names are case-insensitive",
    "dynstiff.analyses.checks.x__band__mutmut_2":
        "positive_scalar(None, ...) for a band's end: the name is used only in the message "
        "of an error that _band catches and replaces with its own, naming the band",
    "dynstiff.analyses.platform_modes.xǁPlatformModesǁdescribe__mutmut_10":
        "np.nanmax(r, initial=None): r is a mode's row of six participations, never empty, "
        "so the initial value is never used",
    "dynstiff.analyses.measured.x_read_measured_modes__mutmut_20":
        "c.split(' [', 2)[0] instead of split(' [', 1)[0]: the first part is the same for "
        "any maxsplit",
    "dynstiff.analyses.measured.x_mac_matrix__mutmut_25":
        "mask.astype(None) instead of astype(float): numpy's default dtype is float64",
    "dynstiff.analyses.measured.x_massless_pairing__mutmut_27":
        "einsum subscripts in upper case: einsum takes either case, the same contraction",
    "dynstiff.analyses.calibrate.x_calibrate__mutmut_595":
        "the start and estimate modes passed to the findings also without measured modes: "
        "calibration_findings reads them only with measured modes",
    **{f"dynstiff.analyses.calibration_checks.x_fit_options__mutmut_{n}":
       "the name given to positive_scalar for a bound: its error is caught and replaced by "
       "fit_options' own, naming bounds" for n in (11, 15, 16)},
    "dynstiff.analyses.calibration_checks.x_calibration_findings__mutmut_73":
        "|u - ln bound| < instead of <= its tolerance: " + _BOUNDARY,
    "dynstiff.analyses.calibration_result.xǁCalibrationResultǁ_repr_html___mutmut_66":
        "range(1, n + 2) for the mode numbers: zip stops at the n measured modes",
    "dynstiff.analyses.measured_frf.xǁFRFComparisonǁplot__mutmut_37":
        "the model's '-' format dropped: semilogy draws a solid line by default",
    "dynstiff.analyses.measured_frf.x_read_measured_frf__mutmut_47":
        "None instead of '' for a record without id1: pyuff's reader gives every record "
        "an id1 ('NONE' when the file has none)",
    "dynstiff.analyses.measured_frf.x_read_measured_frf__mutmut_169":
        "the product of two direction signs (+-1) written as their quotient: the same",
    "dynstiff.analyses.measured_frf.x_read_measured_frf__mutmut_74":
        "0 instead of None as the default of a missing function or data type: neither is "
        "a type dynstiff reads, the record is refused either way",
    "dynstiff.analyses.measured_frf.x__frf_from_csv__mutmut_42":
        "NaN - 0j instead of NaN + 0j for a channel not measured: NaN either way",
    "dynstiff.analyses.measured_frf.x_read_measured_frf__mutmut_101":
        "dtype=None for the abscissa: pyuff gives it as float64",
    "dynstiff.io.exchange.x_even_grid__mutmut_82":
        "the upper clip of searchsorted at f.size + 1 instead of f.size - 1: the even grid "
        "ends at f[-1] (its last point is set to it), so searchsorted never passes f.size - 1",
    **{f"dynstiff.io.exchange.x_{fn}__mutmut_{n}":
       "dtype=float dropped on the frequencies: an FRFResult's are float already, and ints "
       "give the same numbers through the float arithmetic after"
       for fn, n in (("even_grid", 5), ("uff58_records", 40), ("frf_to_control", 25))},
    "dynstiff.io.exchange.x_write_uff58__mutmut_18":
        "pyuff mode 'ADD' instead of 'add' (pyuff then overwrites): the records go to a new "
        "temporary file, where adding and overwriting are the same",
    **{f"dynstiff.io.table.x_read_table__mutmut_{n}":
       "newline='' dropped: the text is split with splitlines(), which takes \\n, \\r\\n "
       "and \\r alike" for n in (4, 7)},
    **{f"dynstiff.io.table.x_read_table__mutmut_{n}":
       "the locale's encoding instead of utf-8: the same on UTF-8 locales (Linux, macOS, "
       "the C locale under PEP 538)" for n in (5, 8)},
    "dynstiff.io.table.x_read_table__mutmut_11":
        "encoding 'UTF-8' instead of 'utf-8': codec names are case-insensitive",
    **{f"dynstiff.maps.store.x_fingerprint__mutmut_{n}":
       "pickle's default protocol instead of protocol=4: the default is 4 on Python 3.8 to "
       "3.13 (the pin keeps fingerprints when a later Python changes it)" for n in (4, 6)},
    "dynstiff.maps.store.xǁCheckpointǁsave__mutmut_5":
        "the reasons also among the plain arrays ('REASON' never matches): overwritten on "
        "the next line, as mutmut_4",
    "dynstiff.maps.store.x_resumed__mutmut_10":
        "the no-checkpoint save callback returns 0 instead of None: its value is not used",
    "dynstiff.maps.dataset.x_to_dataset__mutmut_14":
        "the reasons joined by np.concatenate instead of np.array(dtype=str): lists of str "
        "give the same text array",
    "dynstiff.maps.dataset.x_to_dataset__mutmut_7":
        "the version text of a package that is not installed: the tests run an installed "
        "package, where version() answers",
    "dynstiff.maps.dataset.x_to_dataset__mutmut_197":
        "dtype=None for the check names: a list of str gives a text array anyway",
    "dynstiff.maps.dataset.x_to_dataset__mutmut_328":
        "dtype=None for the tension limits: a robot's limits are floats already",
    **{f"dynstiff.maps.dataset.xǁWorkspaceAccessorǁto_frame__mutmut_{n}":
       "the selected check kept as a scalar coordinate (drop not True): to_frame drops "
       "every non-dimension coordinate before the table" for n in (50, 60, 63)},
    **{f"dynstiff.maps.workspace.xǁ_Progressǁ__init____mutmut_{n}":
       "tqdm's dynamic_ncols (the bar's width on a resized terminal): display only"
       for n in (7, 13)},
    "dynstiff.maps.workspace.x_evaluate_chunk__mutmut_163":
        "the sag ratios not handed to statics_rows, which then computes the same ones",
    "dynstiff.maps.workspace.x_evaluate_chunk__mutmut_164":
        "'' instead of None for the platform modes before the model: read only where the "
        "model was built (which sets them)",
    "dynstiff.maps.workspace.x_evaluate_chunk__mutmut_171":
        "the robot-bound warning filtered by its message alone (category dropped): only "
        "that ClosedFormWarning has the message",
    "dynstiff.maps.workspace.x_evaluate_chunk__mutmut_203":
        "no options for the rows of a failed model: statics_rows reads them only with an "
        "equilibrium",
    "dynstiff.maps.workspace.x_workspace__mutmut_203":
        "the progress bar not shown: display only (stderr), the map is the same",
    "dynstiff.maps.workspace.x_workspace__mutmut_208":
        "the bar advanced by one instead of the saved poses on a resume: display only",
    **{f"dynstiff.io.exchange.x_uff58_records__mutmut_{n}":
       "id4 or id5 under another key: pyuff writes its default, 'NONE', the value given"
       for n in (114, 119)},
    "dynstiff.io.exchange.x_even_grid__mutmut_95":
        "an even point exactly midway between two grid points snapped to the lower one "
        "instead of the upper: it is snapped only when both lie within 1e-9 of the band of "
        "it, i.e. are the same point to rounding",
    "dynstiff.maps.store.xǁCheckpointǁsave__mutmut_4":
        "the reasons also among the plain arrays: the next line overwrites that entry with "
        "the reasons as text",
    "dynstiff.maps.store.xǁCheckpointǁsave__mutmut_10":
        "np.asarray(reasons, dtype=None): a list of str gives a text array anyway (a chunk "
        "never has zero poses, where the dtype would differ)",
    "dynstiff.maps.store.xǁCheckpointǁload__mutmut_3":
        "run.json opened with the locale's encoding instead of utf-8: the same on UTF-8 "
        "locales (Linux, macOS, the C locale under PEP 538); the file is ASCII JSON "
        "(json.dumps escapes non-ASCII) in any case",
    "dynstiff.maps.store.xǁCheckpointǁload__mutmut_31":
        "allow_pickle=None: numpy tests it for truth, None refuses pickles as False does",
    "dynstiff.analyses.interaction.xǁProximityWarningǁ__hash____mutmut_1":
        "a constant hash: sets and dicts of warnings keep their meaning (equality decides), "
        "only slower",
    **{f"dynstiff.analyses.interaction.x_to_frame__mutmut_{n}":
       "the frequencies or gaps without dtype=float: floats (or an empty list) give a float "
       "array anyway" for n in (23, 25, 36, 38)},
    "dynstiff.analyses.optimal_tensions.xǁ_Searchǁ_binds__mutmut_17": _BOUNDARY,
    "dynstiff.analyses.optimal_tensions.xǁ_Searchǁcontinues__mutmut_51": _BOUNDARY,
    "dynstiff.analyses.optimal_tensions.xǁ_Searchǁrun__mutmut_83": _BOUNDARY,
    "dynstiff.analyses.optimal_tensions.xǁ_Searchǁrun__mutmut_112": _BOUNDARY,
    "dynstiff.analyses.optimal_tensions.xǁ_Searchǁrun__mutmut_126": _BOUNDARY,
    "dynstiff.analyses.optimal_tensions.xǁ_Searchǁgradients__mutmut_49":
        "the linearised equilibrium not handed to sensitivities_at, which builds the same "
        "one itself: the same gradients, computed twice",
    "dynstiff.analyses.optimal_tensions.xǁ_Searchǁ_binds__mutmut_12": _BOUNDARY,
    "dynstiff.analyses.optimal_tensions.xǁ_Searchǁrun__mutmut_41": _BOUNDARY,
    "dynstiff.analyses.optimal_tensions.xǁ_Searchǁgradients__mutmut_5":
        "the null-space parameters' value None: a Parameter's value is only reported in "
        "the sensitivities' result (its relative table), which the search does not read",
    "dynstiff.analyses.sensitivity.x__lumped__mutmut_73":
        "the lumped rung's primitives without the tension reference: its linearisation reads "
        "their lengths and loads, not the reference, which enters through the catenary "
        "statics' length derivatives (taken with it; tested against central differences)",
    "dynstiff.analyses.uncertainty.x_propagate_uncertainty__mutmut_142":
        "without a band, the platform search covering 1 Hz instead of 0: it only lengthens "
        "the list beyond the modes every free DOF needs; the first n_modes, the first "
        "platform mode and its row are the same",
    "dynstiff.analyses.uncertainty.x__first_modes__mutmut_3":
        "the list of exactly n_modes continued too: the continuation adds nothing",
    "dynstiff.analyses.sensitivity.x__null_vectors__mutmut_10":
        "the 'moving' flags as floats: 1.0 and 0.0 test as True and False wherever they are "
        "read (never as a mask)",
    **{f"dynstiff.analyses.participation.x_receptance_amplification__mutmut_{n}":
       "frf's inputs left to their default: the loads of the free DOFs, in the order of "
       "the outputs, so the diagonal is the same" for n in (10, 35)},
    "dynstiff.analyses.participation.x_platform_shares__mutmut_114":
        "the platform mass matrix's columns instead of its rows: it is square",
    "dynstiff.analyses.participation.x_modal_data__mutmut_3":
        "'and' for 'or' between the rung and the class: every model of rung 'dsm' is a "
        "FrequencyModel and every FrequencyModel has rung 'dsm' (the static rungs have "
        "their own class)",
    "dynstiff.analyses.sensitivity.x__modal_masses__mutmut_28":
        "einsum's subscripts in capitals: the same contraction",
    "dynstiff.analyses.sensitivity.x_sensitivities_at__mutmut_82":
        "the fields '' instead of None off the exact rung: only the exact rung's forms read "
        "them, and it sets them",
    "dynstiff.analyses.sensitivity.x_sensitivities_at__mutmut_97":
        "the second vector's fields computed even when it is the first: the same fields",
    "dynstiff.analyses.optimal_tensions.xǁ_Searchǁrun__mutmut_166":
        "the parabola's fraction without its upper clip 0.9: on that branch (ratio <= 0.1) "
        "it is 1 / (2 (1 - ratio)) <= 0.56, so the clip never binds",
    "dynstiff.analyses.optimal_tensions.xǁ_Searchǁrun__mutmut_101":
        "the ratio of a step without equilibrium -2 instead of -1: it is compared with 3, "
        "0.1 and -3 only, where both take the same branches",
    "dynstiff.robot.distribution.x_tension_distribution__mutmut_14":
        "t_min passed on without dtype=float: distribution_with_active_set converts it to "
        "float again",
    "dynstiff.robot.feasibility.x__lp__mutmut_17":
        "method 'HIGHS' instead of 'highs': linprog lower-cases the method's name",
    "dynstiff.robot.feasibility.x_limit_bounds__mutmut_17":
        "an infinite upper bound passed as inf instead of None: linprog reads both as no "
        "bound",
    "dynstiff.robot.feasibility.x_diagnose_limits__mutmut_29":
        "0 < best_min <= t_min instead of < t_min: differs only where the largest t_min "
        "that works is t_min itself, a pose whose distribution exists and is never "
        "diagnosed",
    "dynstiff.robot.feasibility.x_diagnose_unreachable__mutmut_36":
        "0 < scale < 2 instead of < 1: scale = (T - lo) / (T* - lo) is below 1 whenever it "
        "is computed (T < T*, T* > lo)",
    "dynstiff.robot.feasibility.x_diagnose_unreachable__mutmut_22":
        "the scale also computed when T* <= lo: with T < T* it is then >= 1 (or a division "
        "by zero at T* = lo exactly), outside (0, 1) like the 0 it replaces",
    "dynstiff.robot.feasibility.x_least_end_tension__mutmut_58":
        "the bracket's top index size - 2 instead of size - 1: differs only when the least "
        "grid tension is at the last point, 5 chords of cable, where the hanging weight "
        "makes T_B larger than at the fold",
    "dynstiff.robot.feasibility.x_least_end_tension__mutmut_62":
        "method None instead of 'bounded': minimize_scalar picks 'bounded' when bounds are "
        "given",
    "dynstiff.robot.feasibility.x_least_end_tension__mutmut_78":
        "<= instead of <: on a tie both are the least tension found",
    "dynstiff.results.xǁFRFResultǁto_frame__mutmut_35":
        "reshape(-2) instead of reshape(-1): numpy takes any negative size as the one to "
        "infer",
    "dynstiff.results.xǁModalResultǁ_repr_html___mutmut_18":
        "the mode numbers' range one longer: zip stops at the shortest, the frequencies",
    "dynstiff.analyses.recommend.x__dsm_error__mutmut_55":
        "closed-form modes from f > lo instead of f >= lo: differs only for a mode exactly "
        "at the band's bottom",
    "dynstiff.analyses.recommend.x__massless_errors__mutmut_66":
        "x^T M x multiplied instead of divided by: scipy's eigh(K, M) returns M-orthonormal "
        "vectors, x^T M x = 1",
    "dynstiff.analyses.recommend.x__massless_errors__mutmut_30": _BOUNDARY,
    **{f"dynstiff.robot.distribution.x_distribution_with_active_set__mutmut_{n}": _WARM
       for n in (77, 134, 142)},
    "dynstiff.robot.distribution.x_distribution_with_active_set__mutmut_88":
        "-2 instead of -1 for a lower side in the guessed active set: only its sign is read",
    "dynstiff.robot.distribution.x_distribution_with_active_set__mutmut_55": _BOUNDARY,
    "dynstiff.robot.distribution.x_distribution_with_active_set__mutmut_30":
        "dtype=float dropped on t_ref: the tensions t_ref + dt are float for integer "
        "references too",
    "dynstiff.results.x_mode_kinds__mutmut_5":
        "dtype=float dropped on platform shares that are floats (NaN included) already",
    "dynstiff.analyses.interaction.x_proximity_warnings__mutmut_32":
        "kind not in 'XXiuXX' instead of 'iu': a dtype's kind is one letter, and X is no "
        "kind",
    "dynstiff.results.xǁFRFResultǁ_repr_html___mutmut_23":
        "the index 1 instead of 0 for an empty channel: it is read only where the channel "
        "has values",
    "dynstiff.results.xǁFRFResultǁ_repr_html___mutmut_22":
        "-2 instead of -1 in place of a non-finite |H|: any negative is below every finite "
        "|H| >= 0, and a channel with none finite reads index 0 either way",
    "dynstiff.analyses.sweep.x_sweep__mutmut_265":
        "the renumbering table one entry longer: it is read at the tracks found (0..n-1) "
        "and at UNTRACKED = -1, the last entry, UNTRACKED in both",
    **{f"dynstiff.analyses.sweep.x_sweep__mutmut_{n}":
       "the one-element row arrays of an infeasible step without their dtype (kind as text "
       "instead of object): every column is cast (astype float / int / str) when the "
       "result is built" for n in (123, 124)},
    **{f"dynstiff.models.dsm.xǁFrequencyModelǁ{name}":
       "a memo's key misspelt where it is looked up or handed to the damped copy: the value "
       "is computed again from the same cables (cost only), the same numbers"
       for name in ("static_error__mutmut_2", "_zero_coefficients__mutmut_1",
                    "_zero_coefficients__mutmut_2", "massless_stiffness__mutmut_1",
                    "massless_stiffness__mutmut_2", "_with_model_damping__mutmut_48",
                    "_with_model_damping__mutmut_49", "_with_model_damping__mutmut_50")},
    "dynstiff.models.dsm.xǁFrequencyModelǁ__init____mutmut_97":
        "tension=None to closed_form_validity, which reads it only to compute the chord "
        "parameters when none are given; they are given",
    "dynstiff.models.dsm.xǁFrequencyModelǁ_static_stiffness__mutmut_9":
        "the zero-frequency coefficients as a 1-D row instead of a (1, 5 n) matrix: the same "
        "product with the assembly map, reshaped to (n_free, n_free) alike",
    "dynstiff.models.dsm.xǁFrequencyModelǁ_with_model_damping__mutmut_24":
        "the damped copy's platform-damping term not reset to None before it is computed: "
        "the copy is made only of an undamped model, whose own term is None already",
    "dynstiff.analyses.modes.x_modes__mutmut_62":
        "the root search without method='wittrick-williams' takes 'auto': this branch is "
        "reached only by a model with cable_kinetic_energies (dsm, exact), continuous rungs "
        "for which 'auto' is Wittrick-Williams",
    **{f"dynstiff.analyses.modes.x_modes__mutmut_{n}":
       "K and the cable-mode counts computed also when no root was found: both return "
       "empty arrays for an empty omega, as the shortcut does" for n in (78, 84, 92)},
    "dynstiff.analyses.modes.x_modes__mutmut_21":
        "getattr without the default 0: every model on the matrix path has n_dof "
        "(eigen_matrix reads model.n_dof), so the default is never taken",
    "dynstiff.models.dsm.xǁFrequencyModelǁ_with_model_damping__mutmut_25":
        "the damped copy shares the undamped model's memo of measured cable errors instead of "
        "a copy of it: an entry depends on the cable, the band and the tension, the same in "
        "both models (the damping is not in it), so either model's entry is the other's",
    "dynstiff.models.dsm.xǁFrequencyModelǁ__init____mutmut_132": _FLOAT,
    "dynstiff.models.dsm.xǁFrequencyModelǁcable_error__mutmut_6": _BOUNDARY,
    "dynstiff.analyses.frf.x_frf__mutmut_64": _BOUNDARY,
    **{f"dynstiff.analyses.frf.x_frf__mutmut_{n}": _FRF_FILTER for n in (57, 59)},
    **{f"dynstiff.analyses.frf.x__receptance__mutmut_{n}": _FRF_FAST for n in (68, 72)},
    "dynstiff.analyses.frf.x__receptance__mutmut_53": _FLOAT,
    "dynstiff.analyses.frf.x_frf__mutmut_77":
        "count at 2 w instead of w: the pole test becomes always true, so H is averaged at "
        "every pre-filtered frequency; 1e-9 from a pole this changes H by O(1e-9)",
    "dynstiff.analyses.frf.x_frf__mutmut_109":
        "the response factor applied to a receptance too: its factor is (i omega)^0 = 1",
    "dynstiff.analyses.interaction.x_proximity_warnings__mutmut_55": _BOUNDARY,
    "dynstiff.analyses.interaction.x_proximity_warnings__mutmut_82":
        "stacklevel=3 of the ProximityWarning: under mutation the trampoline adds a frame, so "
        "the test of the caller's file cannot tell 2 from 3 (stacklevel 1 is killed)",
    "dynstiff.analyses.sweep.x__listed__mutmut_9":
        "asked = (...) instead of asked &= (...) as the first condition: asked is all True "
        "before it",
    "dynstiff.analyses.sweep.x_sweep__mutmut_231":
        "reshape(None) of the 1-D kind array of length n leaves it as it is",
    "dynstiff.analyses.sensitivity.x__null_vectors__mutmut_39":
        "the null vectors of an empty list of modes computed instead of given as empty: "
        "they are empty all the same",
    "dynstiff.analyses.settings.x_analysis_settings__mutmut_47":
        "getattr(scene, 'model') without its default None: every Scene has the field",
    "dynstiff.models.dsm_guard.x_guard_robot__mutmut_9": _BOUNDARY,
    "dynstiff.models.dsm_guard.x_guard_band__mutmut_13": _BOUNDARY,
    "dynstiff.models.dsm_guard.x_static_error__mutmut_83": _EINSUM,
    "dynstiff.models.dsm_guard.x_static_error__mutmut_10":
        "the type named in typing.cast: cast returns its value unchanged at run time",
    **{f"dynstiff.models.dsm_guard.x_guard_band__mutmut_{n}":
       "typing.cast's type given in another case: cast returns its value unchanged"
       for n in (56, 57)},
    **{f"dynstiff.models.dsm_guard.x_guard_band__mutmut_{n}":
       "the memo of a cable already said or measured within tolerance missed: the cable is "
       "measured again at the next wider band (cost only); warn_once still says it once"
       for n in (37, 63)},
    "dynstiff.models.dsm_guard.x_guard_robot__mutmut_3":
        "the early return for a robot bound already said missed: the bound is computed "
        "again (cost only) and warn_once does not say it twice",
    "dynstiff.models.dsm_guard.x_warn_once__mutmut_3":
        "None recorded as the cause issued: _issued is read only for being non-empty",
    "dynstiff.analyses.sensitivity.x__lumped__mutmut_192":
        "the lumped rung's 'moving' flags as floats (ones): 1.0 tests as True wherever they "
        "are read (never as a mask)",
    "dynstiff.analyses.participation.x_modal_data__mutmut_1":
        "max_modes 20001 instead of 20000 by default: a cap no robot's band reaches",
    **{f"dynstiff.analyses.participation.x_receptance_amplification__mutmut_{n}":
       "the 0/0 and inf/inf of the ratio to the static receptance: a robot in equilibrium "
       "has a positive definite K(0), so the static receptance is finite and non-zero and "
       "the ratio is never NaN (an exact pole gives inf / finite = inf)" for n in (54, 65)},
    **{f"dynstiff.robot.distribution.x__active_solution__mutmut_{n}": _WARM
       + "; with a zero lower limit a start off the balance passes the box test, and the "
       "method still ends at the optimum: its iterates are the targets of their active "
       "sets, the start sets only the first step's length (planted and checked against the "
       "3^n active sets, tests/test_robot_distribution.py)" for n in (7, 26)},
    "dynstiff.robot.distribution.x__closest_in_box__mutmut_5":
        "the given active set ignored: the start, feasible, is then taken with no bound "
        "active and the method reaches the same unique optimum in more steps",
    "dynstiff.robot.distribution.x__closest_in_box__mutmut_38":
        "the active entries' placeholder 1.0 instead of 0.0 in target: every free entry is "
        "overwritten, every active one is set from bound",
    "dynstiff.robot.distribution.x__closest_in_box__mutmut_80":
        "None instead of inf for a zero step component: those entries are replaced by inf "
        "on the next line (|p| <= 1e-12 scale), so argmin sees the same numbers",
    "dynstiff.robot.distribution.x__closest_in_box__mutmut_116":
        "p <= 0 instead of < 0 for the bound met: the blocking entry has |p| > 1e-12 scale "
        "(others have infinite room), never p = 0",
    "dynstiff.robot.distribution.x__closest_in_box__mutmut_176":
        "None instead of nan freeing a bound: numpy stores None in a float array as nan",
    **{f"dynstiff.cli.common.x_check_outputs__mutmut_{n}":
       "float('INF') instead of float('inf'): float() reads either case" for n in (123, 152)},
    "dynstiff.cable.psi.x_irvine_symmetric_roots__mutmut_49": _BOUNDARY,
    "dynstiff.cable.guard.x_guard_cable__mutmut_16":
        "the envelope's pre-filter with the mean tension instead of the one asked: the "
        "warning is decided by the measured error, with the tension asked, which both "
        "envelopes bound (on the steep cable whose chord tension is 34 % below the mean: "
        "envelopes 52 and 22, measured 0.23); they differ only where the measured error "
        "exceeds guard_rtol and one envelope does not",
    **{f"dynstiff.analyses.freqgrid.x_refined_grid__mutmut_{n}":
       "dtype=float dropped on the modes: numeric modes (ints too) give the same grid, the "
       "product with the float offsets being float" for n in (31, 33)},
    "dynstiff.analyses.freqgrid.x_refined_grid__mutmut_50":
        "f (1 - d) instead of f (1 + d): d holds every offset with both signs, so the same "
        "set of points",
    "dynstiff.robot.waypoints.x__blend__mutmut_14":
        "t <= tb instead of t < tb: at t = tb the cruise branch gives 0.5 acc tb^2 + "
        "acc tb 0.0, bit for bit the blend's",
    "dynstiff.cable.psi.x_check_frequency_range__mutmut_14": _BOUNDARY,
    "dynstiff.cable.psi.x_mode_count_psi__mutmut_22":
        "the even branches' sign +2 instead of +1: only the sign of the product is tested",
    "dynstiff.cable.guard.x_closed_form_local_error__mutmut_28": _BOUNDARY,
    "dynstiff.cable.guard.x_closed_form_validity__mutmut_66": _BOUNDARY,
    "dynstiff.analyses.reduced.x__dK_domega2__mutmut_2":
        "the complex step 1e-20 / omega instead of 1e-20 omega: a complex step has no "
        "cancellation and an h^2 error, so both give dK/domega^2 to rounding above 1e-3 rad/s",
    "dynstiff.analyses.reduced.x__floor__mutmut_10":
        "the largest entry of an empty matrix 1 instead of 0: no entry is compared with it",
    "dynstiff.analyses.reduced.x__floor__mutmut_5": _FLOAT,
    "dynstiff.analyses.damped.x__perturbation_estimates__mutmut_8":
        "the NaN fill written as NaN - 0j: still NaN, overwritten or tested with isfinite only",
    **{f"dynstiff.analyses.damped.x_damped_modes__mutmut_{n}":
       "the NaN fill written as NaN - i NaN or NaN + 2i NaN: still NaN, overwritten or "
       "tested with isnan" for n in (36, 38)},
    "dynstiff.analyses.damped.x_damped_modes__mutmut_2":
        "max_iter 81 instead of 80: converging roots take at most 45 secant steps (the "
        "synthetic triple root of the tests, converging linearly, under 75)",
    "dynstiff.analyses.damped.x__perturbation_estimates__mutmut_32":
        "K_d + K_u instead of K_d - K_u in the estimate: the extra 2 x^T K_u(omega_r) x is 0 "
        "at the undamped root (x its null vector); the estimate moves by 1e-8 of its own "
        "error, the converged root not at all",
    **{f"dynstiff.analyses.eigen_matrix.x_modes__mutmut_{n}":
       "the local-mode floor 1e-24 of the platform energy against phi^T M phi, which is 1 "
       "to 1e-15 for mass-normalised modes (>= for >, / for *)" for n in (36, 37)},
    **{f"dynstiff.plot.common.x_mode_frequencies__mutmut_{n}":
       "reshape(-2) for reshape(-1): numpy reads any negative size as the one unknown"
       for n in (16, 39)},
    "dynstiff.io.caspr.x__read_body__mutmut_75":
        "n_q + 4 leading zeros in the default q: q is read as q[:3] (zeros either way) and "
        "q[-4:] (the same unit quaternion) only",
    "dynstiff.scenes.writer.x__value__mutmut_7":
        "more characters stripped from a value's text: it ends in a digit, inf, nan or a "
        "quote, none of them stripped",
    "dynstiff.cli.report.x__cmd_report__mutmut_24":
        "info(None) for info(args): info switches to stderr only for --csv/--json '-', "
        "which demo and report do not have: stdout both ways",
    "dynstiff.cli.report.x__common__mutmut_2":
        "add_pose(p, lengths=None): add_pose only tests lengths for truth, None as False",
    "dynstiff.cli.sweep.x__cmd_sweep__mutmut_231":
        "matplotlib.use('AGG'): backend names are case-insensitive",
    "dynstiff.cli.sweep.x__cmd_sweep__mutmut_304":
        "to_string(index=None): pandas treats None as False there, the same text",
    "dynstiff.plot.accuracy.x__label_offsets__mutmut_42":
        "dy[j] >= 0 for > 0: offsets start at 4 and step 4, -12, 20, -28 ...: never 0",
    "dynstiff.plot.accuracy.x__label_offsets__mutmut_43":
        "dy[j] > 1 for > 0: the offsets 4, -12, 20, -28 ... never lie in (0, 1]",
    "dynstiff.plot.workspace.x_worst_case__mutmut_19":
        "min over [] (no dimension reduced) with skipna=False returns the array unchanged "
        "(values, dims, coords, name, attrs)",
    "dynstiff.plot.workspace.x_worst_case__mutmut_31":
        "the same for band_margin",
    "dynstiff.plot.sweep.x__gap_bridges__mutmut_20":
        "dtype=float dropped: every non-empty list holds a NaN and x, the table are "
        "float64: float64 either way",
    "dynstiff.plot.sweep.x__gap_bridges__mutmut_22":
        "the same (dtype=None)",
    "dynstiff.plot.sweep.x__gap_bridges__mutmut_24":
        "the same",
    "dynstiff.plot.sweep.x_plot_veering__mutmut_40":
        "values read with dtype=None: SweepResult.values is always float64 (validated or "
        "a cumsum of norms)",
    "dynstiff.plot.sweep.x_plot_veering__mutmut_55":
        "any_gap = None for False: only tested for truth",
    "dynstiff.plot.sweep.x_plot_veering__mutmut_212":
        "ax.grid(None, alpha=0.3): matplotlib turns the grid on when visible is None and "
        "keywords are given",
    "dynstiff.plot.sweep.x_plot_veering__mutmut_220":
        "x.size >= 1 in the log-axis test: one finite value cannot satisfy max >= 10 min "
        "> 0",
    "dynstiff.cli.simulate.x__cmd_simulate__mutmut_155":
        "resp = None in the --target/--trajectory branch: nothing reads resp after it "
        "there (table from tr.to_frame(), plot from tr, pose from traj)",
    "dynstiff.plot.time.x_plot_tracking__mutmut_39":
        "'TAB:BLUE' for 'tab:blue': matplotlib reads colour names case-insensitively, "
        "same RGBA",
})

def _definitions():
    """{top-level function or class name: [dotted modules defining it]} of the package."""
    import ast
    import pathlib
    root = pathlib.Path(__file__).resolve().parents[1]
    out = collections.defaultdict(list)
    for path in sorted((root / "dynstiff").rglob("*.py")):
        module = ".".join(path.relative_to(root).with_suffix("").parts)
        for node in ast.parse(path.read_text()).body:
            if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
                out[node.name].append(module)
    return out


def _relocated(equivalent):
    """The keys of ``equivalent`` moved to the module that defines their function today (a
    module split moves functions; their mutant numbers, which count within a function, do
    not change). Among several modules defining the name, the one sharing the old module's
    name wins."""
    defs = _definitions()
    out = {}
    for key, why in equivalent.items():
        m = re.match(r"(dynstiff\.[\w.]+?)\.(x_(\w+?)__mutmut_\d+|xǁ(\w+)ǁ.*)$", key)
        module, name = m.group(1), m.group(3) or m.group(4)
        where = defs.get(name, [])
        if where and module not in where:
            module = max(where, key=lambda w: (w.rsplit(".", 1)[0] == module.rsplit(".", 1)[0],
                                               w.startswith(module)))
        out[f"{module}.{m.group(2)}"] = why
    return out


EQUIVALENT.update({f"dynstiff.scenes.writer.x_scene_text__mutmut_{n}":
                   "a trajectory without a note gets None instead of '' (or no default): "
                   "_trajectory_lines writes a note only when it is truthy, the same for both"
                   for n in (184, 186)})
EQUIVALENT.update({
    "dynstiff.scenes.writer.x__value__mutmut_1":
        "rstrip() instead of rstrip('\\n'): a value's text ends in a digit, inf, nan, a "
        "bracket or a quote, never in other whitespace",
    "dynstiff.scenes.writer.x__value__mutmut_5":
        "the dumped key 'V' instead of 'v': one character either way, cut off by [4:]",
})
EQUIVALENT.update({f"dynstiff.timedomain.damping.xǁTimeDampingǁaxial_per_cable__mutmut_{n}":
                   "dtype=float dropped on a tuple of Python floats (__post_init__ stores "
                   "several dashpots so): float64 anyway" for n in (14, 16)})
EQUIVALENT.update({
    "dynstiff.plot.frf.x_plot_frf__mutmut_187":
        "np.errstate(invalid=None) around np.degrees(np.angle(h)), which raises no invalid "
        "warning for any complex input (nan and inf included, checked under all='raise')",
    "dynstiff.plot.frf.x_plot_frf__mutmut_202":
        "break for continue on a None axes: ax is never None after the figure is made, so "
        "the branch runs only for ax_ph, the last item of the loop",
})
EQUIVALENT.update({f"dynstiff.cli.console.x__tqdm__mutmut_{n}":
                   "tqdm's file left to its default, which is sys.stderr when the bar is made"
                   for n in (1, 4)})
EQUIVALENT.update({
    **{f"dynstiff.report.cable.x_write_report__mutmut_{n}":
       "to_csv(index=None) instead of index=False: pandas writes no index either way"
       for n in (36, 43)},
    "dynstiff.report.cable.x_write_report__mutmut_3":
        "matplotlib.use('agg') instead of 'Agg': backend names are not case-sensitive",
})
EQUIVALENT.update({
    "dynstiff.robot.pose.xǁPoseǁ__post_init____mutmut_24":
        "the fallback of coordinates that are not numbers np.zeros(1) instead of "
        "np.zeros(0): any shape but (3,) gives the same refusal",
})
EQUIVALENT.update({
    "dynstiff.timedomain.pendulum.dynamics.x_evaluate_rhs__mutmut_212": _EINSUM,
    "dynstiff.timedomain.pendulum.dynamics.x_evaluate_rhs__mutmut_169":
        "slice(4 n) for slice(0, 4 n): the same slice",
    **{f"dynstiff.timedomain.pendulum.model.xǁCablePendulumǁstate_scale__mutmut_{n}":
       "dtype=float dropped on the excitation's omega, float64 already (excitation_at "
       "converts it)" for n in (7, 9)},
})
EQUIVALENT.update({
    "dynstiff.timedomain.pendulum.floquet.x__by_modulus__mutmut_6":
        "take_along_axis's axis=1 dropped: numpy 2.3+ defaults to the last axis, the same "
        "for these 2-D arrays (older numpy would raise, killing it)",
    "dynstiff.timedomain.pendulum.radau.x_mirror_bases__mutmut_40":
        "w <= 0 for w < 0 on the eigenvalues of a mirror matrix, exactly +-1: the same columns",
    "dynstiff.timedomain.pendulum.floquet.x__floquet_group__mutmut_285":
        "err < orbit_tol for err <= orbit_tol on an averaged response's last residual: "
        "differs only when the residual equals the tolerance to the last bit",
})
EQUIVALENT.update({
    "dynstiff.cable.lumped_graded.x_graded_chain__mutmut_232":
        "closure(f0 + step) <= res for <: differs only on an exact tie of the closures, at "
        "rounding level near the solution, where either branch moves to an equally closed "
        "chain",
    "dynstiff.cable.lumped_graded.x_graded_chain__mutmut_2":
        "max_iter default 201 for 200: differs only for a chain that needs exactly 201 "
        "iterations (Newton with a line search on the strictly convex complementary energy "
        "closes the test chains in under 30)",
    "dynstiff.cable.lumped_graded.xǁGradedChainǁ_saddle__mutmut_117":
        "shape=None: COO infers (4N+3, 4N+3) from the largest indices, end B's last "
        "coordinate 4N+2 included: the same shape",
    "dynstiff.cable.lumped_graded.xǁGradedChainǁfixed_end_frequencies__mutmut_34":
        "diag_pivot_thresh=None: SuperLU's default threshold is 1.0, the value given",
    "dynstiff.cable.lumped_graded.xǁGradedChainǁfixed_end_frequencies__mutmut_68":
        "dtype=None on the LinearOperator: inferred from a matvec of zeros, float64, the same",
    "dynstiff.cable.lumped_graded.xǁGradedChainǁ_saddle__mutmut_138":
        "np.zeros(1, int) when no node is clamped: every caller clamps node 0, so the branch "
        "is never taken",
    "dynstiff.cable.lumped_graded.xǁGradedChainǁfixed_end_frequencies__mutmut_99":
        "ncv = 3 n + 1 instead of 2 n + 1 (both at least 40): the Lanczos basis size changes "
        "the work, not the eigenvalues eigsh converges to at tol = 0",
    "dynstiff.cable.lumped_graded.x_graded_edges__mutmut_70":
        "the start table's sinh points spread to L0 + s_low instead of L0 (clipped to [0, "
        "L0]): the table only starts three Newton steps on the exact Phi, which end at the "
        "same edges to 1e-14 of L0 (measured on 9 gradings)",
    "dynstiff.cable.lumped_graded.x_graded_edges__mutmut_45":
        "the start table's uniform points from 1 m instead of 0: the sinh points cover [0, "
        "L0] already, and the Newton steps end at the same edges to 1e-14 of L0 (measured on "
        "9 gradings)",
    "dynstiff.models.base.xǁPlatformModelǁdamping_text__mutmut_8":
        "getattr's default None for 0.0 when a model has no platform_damping_ratio: both are "
        "false, the part is left out either way",
    "dynstiff.models.base.xǁPlatformModelǁdamping_text__mutmut_18":
        "getattr's default None for 0.0 when a model has no cable_loss_factor: both are "
        "false, the part is left out either way",
    "dynstiff.models.base.xǁPlatformModelǁdamping_text__mutmut_29":
        "max's default None for 0.0: taken only for a robot without cables, which no robot is"
        " (a Robot needs at least as many cables as free DOFs)",
    "dynstiff.timedomain.energy_scheme.xǁEnergyStepperǁ_single__mutmut_172":
        "res >= for res > against the divergence bound: differs only when the residual equals"
        " 1e3 times the first one (or the tolerance) to the last bit",
    "dynstiff.timedomain.discrete_gradient.x__mean_dashpot__mutmut_12":
        "dtype=float dropped on the dashpots, a float array already (Dynamics.c_ax): the same"
        " values",
    "dynstiff.timedomain.discrete_gradient.x__mean_dashpot__mutmut_21":
        "the one-chain dashpot kept as shape (1,) instead of (): it broadcasts against the "
        "chain's (N,) lengths to the same values",
    "dynstiff.timedomain.discrete_gradient.x_discrete_gradient_force__mutmut_9":
        "the chain-by-chain branch taken for equal chains too: it computes the same force, "
        "only slower (the two branches agree on every test robot to rounding)",
    "dynstiff.timedomain.discrete_gradient.x_discrete_gradient_force__mutmut_11":
        "segments compared with the second chain's count instead of the first's: all equal to"
        " one exactly when all equal to the other",
    "dynstiff.timedomain.discrete_gradient.x_secant_elements__mutmut_123":
        "(b < 1) for (b < 0) in the taut-to-slack branch: reached only after the both-taut "
        "case (a >= 0, b >= 0) is taken, so with a >= 0 it selects b < 0 either way",
    "dynstiff.timedomain.discrete_gradient.x__mean_dashpot__mutmut_35":
        "errstate invalid=None (warn) for ignore: the 0/0 of a segment that neither moves nor"
        " leaves l0 exactly warns, whose result np.where discards: the same values",
    "dynstiff.timedomain.response.xǁTimeResponseǁspectrum__mutmut_29":
        "detrend=\"constant\" dropped from scipy.signal.periodogram: \"constant\" is its default "
        "(scipy 1.17 signature), the same call",
    "dynstiff.timedomain.response.xǁTimeResponseǁspectrum__mutmut_40":
        "max(initial=None) for initial=0.0 on amp[1:]: None means no initial value, and "
        "amp[1:] is never empty (at least 8 records give at least 5 bins) of non-negative "
        "amplitudes, so the same maximum",
    "dynstiff.timedomain.response.xǁTimeResponseǁspectrum__mutmut_60":
        "idx >= 0 for idx > 0: scipy.signal.find_peaks never returns the first (or last) "
        "sample, so index 0 is never among the peaks to filter",
    "dynstiff.timedomain.response.xǁTimeResponseǁspectrum__mutmut_93":
        "den < 1 for den < 0: at a find_peaks maximum den = -(a + b) with a, b >= 0 the log "
        "drops to the two neighbours, so it differs only for den == 0, i.e. three bins of "
        "exactly equal log amplitude (an exact 3-bin flat top, or amplitudes all below "
        "2.2e-308 m clamped to tiny); a computed spectrum gives such a tie only by floating-"
        "point accident, no reasonable input produces it reliably",
    "dynstiff.cable.lumped_elements.x_interior_banded__mutmut_18":
        "rows <= 3 N keeps end node B's first row against node N-1's columns: shifted, it is "
        "row n of an n x n matrix, dropped by the upper form (row > column) and stored in the"
        " general form's slots below the last row, which LAPACK's banded solvers never read "
        "(A[i, j] for i <= n - 1 only)",
    "dynstiff.models.base.xǁPlatformModelǁdamping_text__mutmut_31":
        "max without its default over the cables' viscous damping: differs only for a robot "
        "without cables (a ValueError), which no robot is",
    "dynstiff.models.base.xǁPlatformModelǁdamping_text__mutmut_32":
        "max's default 1.0 for 0.0: taken only for a robot without cables, which no robot is",
    "dynstiff.models.base.xǁPlatformModelǁdamping_text__mutmut_35":
        "max's default None for 0.0 over the cables' loss factors: taken only for a robot "
        "without cables",
    "dynstiff.models.base.xǁPlatformModelǁdamping_text__mutmut_37":
        "max without its default over the cables' loss factors: differs only for a robot "
        "without cables",
    "dynstiff.robot.equilibrium.xǁEquilibriumǁ_per_cable__mutmut_2":
        "the per-cable cache kept under the key None instead of \"_per_cable_cache\" in the "
        "record's __dict__: a private key either way, read and written by this method only",
})
EQUIVALENT.update({
    "dynstiff.cable.lumped_chain_dynamics.x_chain_fixed_end_frequencies__mutmut_50":
        "check_finite=True on the banded stiffness: only a check, the matrix of an "
        "equilibrium is finite: the same eigenvalues",
    "dynstiff.cable.lumped_chain_dynamics.x_chain_fixed_end_frequencies__mutmut_42":
        "check_finite left to its default (True): only a check on a finite matrix, the same "
        "eigenvalues",
    "dynstiff.cable.lumped_chain_dynamics.x_chain_fixed_end_frequencies__mutmut_32":
        "lower=None for False: a false value, eig_banded reads the upper form either way",
    "dynstiff.cable.lumped_chain_dynamics.x_chain_fixed_end_frequencies__mutmut_38":
        "lower left to its default, False: the same call",
    "dynstiff.cable.lumped_chain_dynamics.x_chain_end_dynamic_stiffness__mutmut_157":
        "check_finite=None for False: a false value, solve_banded skips the check either way",
    "dynstiff.cable.lumped_chain_dynamics.x_chain_end_dynamic_stiffness__mutmut_176":
        "the pole's inf block made without the chain's dtype: stored into the output array of"
        " that dtype, inf (+0j) either way",
    "dynstiff.cable.lumped_chain_dynamics.x_chain_matrices__mutmut_14":
        "shape left to COO's inference: the diagonal has an entry in every DOF, the last "
        "included, so (n_dof, n_dof) either way",
    "dynstiff.cable.catenary_batch.x__newton__mutmut_50":
        "res < _RTOL for <=: differs only when the residual equals 1e-13 to the last bit",
    "dynstiff.cable.catenary_batch.x_states_for_tensions__mutmut_12":
        "the warm start dropped: Newton from the straight cable reaches the same taut "
        "solution (to its 1e-13 residual), the start sets the cost only",
    "dynstiff.cable.catenary_batch.x__newton__mutmut_137":
        "the taut-branch test reads only the sign of dT/dL0: with det's second product added "
        "instead of subtracted the sign is the same on every catenary checked (72, level, "
        "rising and falling chords, from taut to 20 times slack)",
    "dynstiff.cable.catenary_batch.x__newton__mutmut_166":
        "as _137: F10 / c0 for F10 c0 in the second component leaves the sign of dT/dL0 "
        "unchanged on the 72 catenaries checked",
    "dynstiff.cable.catenary_batch.x__newton__mutmut_169":
        "as _137: c1 for c0 in the second component leaves the sign of dT/dL0 unchanged on "
        "the 72 catenaries checked",
    "dynstiff.cable.catenary_batch.x__newton__mutmut_46":
        "the residual multiplied by the scale instead of divided: Newton converges to "
        "rounding either way (measured 1e-17 to 3e-14 both ways on six cables from 0.4 to 15 "
        "m), so the same solution; only the reported residual's rounding-level value differs",
    "dynstiff.robot.forward_statics.x__kinematic_guess__mutmut_14":
        "the least-squares start of the free DOFs lowered by 1.5 instead of 0.5 times the "
        "anchors' height spread: forward_statics uses the guess only when every DOF is free "
        "(held DOFs need initial_pose), so x0 is a start only; the fit ends at the same "
        "chords (the forward statics test finds the same pose)",
    "dynstiff.robot.forward_statics.x__kinematic_guess__mutmut_10":
        "the least-squares start moved by 1 m in x: as _14, a start only (x is free whenever "
        "the guess is used)",
    "dynstiff.robot.forward_statics.x_forward_statics__mutmut_8":
        "range(7) for range(6): adds the index 6 to the held set, which is only intersected "
        "with {0, 1, 2} and {3, 4, 5}",
    "dynstiff.robot.forward_statics.x_forward_statics__mutmut_2":
        "max_iter default 51 for 50: differs only for a pose whose Newton needs exactly 51 "
        "iterations (the test poses converge in a few)",
    "dynstiff.cable.catenary_batch.x_taut_catenaries__mutmut_53":
        "a finite start with H <= 0 or L0 <= 0 kept instead of replaced: Newton keeps such a "
        "cable off the taut branch (H > 0 is required), so it is retried from the straight "
        "cable, the replacement's own start: the same solution",
    "dynstiff.cable.catenary_batch.x__solve__mutmut_9":
        "errstate all=None for ignore: a cable that diverges warns on the way; its non-finite"
        " residual marks it not converged either way, the same result",
    "dynstiff.cable.catenary_batch.x_taut_catenaries__mutmut_114":
        "pending[done] = None for False: None stored into a bool array is False",
    "dynstiff.cable.mpmath_reference.x__entries_to_dps__mutmut_7":
        "starting precision from psi_est forced to 0 (extra = 0): precision/work only; at too"
        " low a precision tau = 1 - tan(psi)/psi is exactly 0 (lost = inf, doubled) or "
        "rounding noise (measured loss ~ all working digits), so need > work and the loop "
        "raises the precision until the measured cancellation is covered, as in the real "
        "code; even psi ~ 1e-960 (float inputs) stays under 4000 digits by doubling",
    "dynstiff.cable.mpmath_reference.x__entries_to_dps__mutmut_33":
        "extra only for psi_est > 1, where -log10(psi_est) < 0 makes it 0 anyway: extra is "
        "always 0, same as _7 (precision/work only)",
    "dynstiff.cable.mpmath_reference.x__entries_to_dps__mutmut_24":
        "3 instead of 2 log10(1/psi) extra starting digits: higher start precision only; the "
        "measured loss decides acceptance (need <= work), start work <= ~1040 digits for any "
        "float psi_est >= 5e-324, and the start is not checked against the 4000 limit; "
        "results agree to dps digits",
    "dynstiff.cable.mpmath_reference.x__entries_to_dps__mutmut_59":
        "need < work instead of <=: only when need == work exactly, one more pass at need + "
        "15 digits, which then accepts (precision/work only; the changed path could only "
        "raise where need == work falls in (4000, 4015], a coincidence at the precision "
        "limit)",
    "dynstiff.cable.mpmath_reference.xǁ_Evaluatorǁsub__mutmut_3":
        "a != 0 and b != 0: differs only when exactly one operand is 0 (q = 0: sag_term = 0; "
        "lambda^2 = 0 in D), where a - b is exact (no digit lost) and the real code only adds"
        " its 1 digit of slack; r == 0 is impossible there; the remaining count still bounds "
        "the true loss, so the result is still good to dps digits (precision/work only)",
    "dynstiff.cable.mpmath_reference.xǁ_Evaluatorǁsub__mutmut_5":
        "a != 1 or b != 0: skips a == 1, b == 0 (D = 1 - 0 for lambda^2 = 0, exact, 1 slack "
        "digit less) and counts a == b == 0 (r == 0 -> inf), which never happens (k_s = 0 "
        "would need cot(beta L) exactly 0; K0/D = 0 needs EA = 0 with m_axial != 0; beta = 0 "
        "raises earlier): precision/work only",
    "dynstiff.cable.mpmath_reference.x_end_stiffness_mp__mutmut_2":
        "default dps 51 instead of 50: result good to >= 50 digits either way; only the "
        "working precision (digits beyond dps of the as_mpmath values, which are not "
        "specified) differs",
    "dynstiff.cable.mpmath_reference.x__to_output__mutmut_3":
        "dtype=None: np.array of a list of Python complex numbers is complex128 anyway",
    "dynstiff.cable.mpmath_reference.x_irvine_symmetric_roots_mp__mutmut_90":
        "(current numbering) verify=None instead of False in the Anderson findroot call: "
        "mpmath.findroot only tests 'if verify and ...', None is falsy",
    "dynstiff.cable.mpmath_reference.x_irvine_symmetric_roots_mp__mutmut_104":
        "(current numbering; the old run's _90) |g(x)| <= tol instead of < in the check after"
        " Anderson: differs only when the residual equals the rounded 10^-dps exactly; even "
        "then both branches return a root good to dps digits (accepted point, or bisection)",
    "dynstiff.robot.forward_statics.x_forward_statics__mutmut_91":
        "step >= 1e-4 for >: the step halves from 1 (2^-k) and never equals 1e-4",
    "dynstiff.robot.forward_statics.x_forward_statics__mutmut_90":
        "the line search starts at twice the Newton step: a longer first trial, halved until "
        "the residual falls, so the iteration ends at the same equilibrium (to tol), by "
        "another path",
    "dynstiff.robot.equilibrium.xǁEquilibriumǁ_per_cable__mutmut_6":
        "the per-cable cache under another private key of the record's __dict__, read and "
        "written by this method only",
    "dynstiff.robot.equilibrium.xǁEquilibriumǁ_per_cable__mutmut_7":
        "the per-cable cache under another private key of the record's __dict__, read and "
        "written by this method only",
    "dynstiff.cable.lumped_chain.x__force_space_start__mutmut_185":
        "the force-space Newton's own start with the weight of N + 1 instead of N - 1 half "
        "segments: a start only, Newton on the strictly convex energy ends at the same force "
        "(the start nodes equal the equilibrium to 1e-12 m)",
    "dynstiff.robot.forward_statics.x_forward_statics__mutmut_106":
        "res_t <= res for <: accepts a trial whose residual equals the current one to the "
        "last bit (at rounding level near convergence), where halving it instead ends at the "
        "same equilibrium to tol",
    "dynstiff.cable.lumped_chain.x__newton__mutmut_124":
        "step.reshape(-2, 3) vs reshape(-1, 3): numpy (2.4.6, no warning even with -W error) "
        "treats any negative dimension as the one inferred dimension, so the shape is the "
        "same (n, 3) for every step, including the empty one (N = 1)",
    "dynstiff.cable.catenary_batch.x_sag_ratios__mutmut_43":
        "the clip's lower bound 0 dropped: s*, where V(s*) / H = h / l_h, lies in [0, L0] for"
        " a hanging catenary (V0 <= V(s*) <= V0 + w0 L0), so the bound catches rounding only",
    "dynstiff.cable.exact_condense.x_condense__mutmut_24":
        "check_finite=None for False: a false value, lu_factor skips the check either way",
    "dynstiff.cable.exact_condense.x_condense__mutmut_36":
        "check_finite=True on the LU solve: only a check; the mesh matrices of a finite state"
        " at a finite frequency are finite, the same values",
    "dynstiff.cable.exact_condense.x_condense__mutmut_35":
        "check_finite left to its default (True): only a check on finite matrices, the same "
        "values",
    "dynstiff.cable.exact_condense.x_condense__mutmut_26":
        "check_finite left to its default (True) on the LU factorisation: only a check on "
        "finite matrices, the same factors",
    "dynstiff.cable.exact_condense.x_condense__mutmut_39":
        "Z_rr.shape[1] for shape[0]: Z_rr is square",
    "dynstiff.cable.exact_condense.x_condense__mutmut_45":
        "check_finite=None for False: a false value, lu_solve skips the check either way",
    "dynstiff.cable.exact_condense.x_condense__mutmut_48":
        "check_finite left to its default (True): only a check on finite matrices, the same "
        "values",
    "dynstiff.cable.exact_condense.x_condense__mutmut_99":
        "einsum's subscripts in capitals (\"IJ,IJ->J\"): the same contraction",
})
_TAG_CASE = "an upper-case closing tag: HTML tag names are case-insensitive, the same page"
EQUIVALENT.update({f"dynstiff.report.html.x_html_page__mutmut_{n}": _TAG_CASE
                   for n in (43, 103, 193, 197)})
EQUIVALENT.update({
    "dynstiff.robot.robot.xǁRobotǁ__post_init____mutmut_49":
        "max(initial=None) in the message of a coordinate beyond the limit: the array is not "
        "empty there, so the same maximum",
})
EQUIVALENT.update({
    "dynstiff.models.lumped_statics.x_lumped_equilibrium__mutmut_114":
        "alpha <= 1e-6 for <: alpha takes only the values 2^-k, exact in floating point, "
        "and 1e-6 is no power of two, so both stop at the same halving (2^-20)",
})
EQUIVALENT.update({
    "dynstiff.cable.dsm.x__entries_from__mutmut_14":
        "np.errstate(invalid='ignore') dropped around the closed-form entries: no 0/0 or "
        "inf/inf arises there (120,000 frequencies from 0 to the model's limit on three "
        "sags, damped and undamped, ran under invalid='raise' without one)",
})
_SP = "dynstiff.analyses.sensitivity_parameters."
EQUIVALENT.update({
    f"{_SP}x__parameter__mutmut_185":
        "str.rindex for str.index of x, y or z in 'xyz', where each occurs once",
    f"{_SP}x__parameter__mutmut_232":
        "str.rindex for str.index of x, y or z in 'xyz', where each occurs once",
    f"{_SP}x__parameter__mutmut_312":
        "np.asarray(t_ref) without float: the reference is checked as real numbers by "
        "frequency_sensitivities and the statics (a float array either way); only a list "
        "of Python complex numbers given straight to expand_parameters tells them apart",
})
EQUIVALENT.update({
    "dynstiff.scenes.loader.x_read_scene__mutmut_288":
        "np.array(attachments) without dtype=float: Robot converts them to a float array "
        "(real_array) before any use",
})
_CS = "dynstiff.cable.catenary_solve."
EQUIVALENT.update({
    f"{_CS}x__initial_guesses__mutmut_41":
        "a starting-guess branch boundary (lh <= 1e-6 / L for 1e-6 L): the solution is the "
        "same (unique for given L0 and ends, checked by its residual)",
    f"{_CS}x__initial_guesses__mutmut_85":
        "V0's starting guess beyond lam = 700 with h + L0 for h - L0: the solution is the "
        "same (unique for given L0 and ends, checked by its residual; other guesses tried)",
    f"{_CS}x_solve_catenary__mutmut_87":
        "the vertical branch's bound 1e-14 / L for 1e-14 L: within 1e-12 of vertical the "
        "inclined and vertical solutions agree to 8e-15 (measured at L = 0.01 and 10 m)",
    f"{_CS}x__newton__mutmut_31": _BOUNDARY,
    f"{_CS}x__newton__mutmut_75": _BOUNDARY,
    f"{_CS}x__validate_ends__mutmut_21":
        _BOUNDARY + " (a coordinate of exactly 1e100 m, the limit)",
})
EQUIVALENT.update({f"dynstiff.scenes.loader.x_read_scene__mutmut_{n}":
                   "the line given to the error of np.asarray(unstretched_lengths, float), "
                   "which cannot fail on the list of numbers the type check let through"
                   for n in (339, 352)})
_LR = "dynstiff.models.lumped_robot.xǁLumpedMassModelǁ_node_matrix__mutmut_"
EQUIVALENT.update({
    f"{_LR}8": "np.array(platform_block) without dtype=float: both callers pass float "
               "arrays (the platform mass matrix, zeros)",
    f"{_LR}14": "4 (N_i - 1) entries written per cable instead of 3 (N_i - 1): the overflow "
                "lies in later cables' ranges, each rewritten from its own start when its "
                "turn comes, and the last cable's past n_dof, which the slice drops",
})
EQUIVALENT.update({
    "dynstiff.models.lumped.xǁLumpedLinearModelǁnode_shapes__mutmut_24":
        "reshape(n, -2, 3) infers like -1 (numpy 2.4; empty blocks included)",
    "dynstiff.timedomain.dynamics.xǁDynamicsǁset_model__mutmut_13":
        "np.asarray(segments) without dtype=int64: the model's segments are an int64 array "
        "already (np.array(..., dtype=int) on this 64-bit platform)",
})
EQUIVALENT.update({
    "dynstiff.models.lumped_robot.xǁLumpedMassModelǁtangent_unchecked__mutmut_187":
        "shape dropped from the COO tangent: inferred from the largest index, n_dof - 1, "
        "which is always there (the diagonal block of the last interior node, or the full "
        "platform block when no cable has one)",
})
EQUIVALENT.update({f"dynstiff.scenes.loader.x_read_scene__mutmut_{n}":
                   "the section dropped from an error's line lookup, so the key is searched "
                   "in the whole file: band_hz, forbidden_band_hz and box are keys of one "
                   "section only (a key unknown to its section is refused before), the same "
                   "line" for n in (450, 523)})
EQUIVALENT.update({
    "dynstiff.robot.robot.xǁRobotǁequilibrium__mutmut_44":
        "start= not passed on to the inverse statics: a first guess only, documented to "
        "reach the same equilibrium (a failed warm start is solved without it); only the "
        "work differs, which the tests do not time",
})
_SL = "dynstiff.analyses.sensitivity_lumped.xǁLumpedLinearisationǁ"
EQUIVALENT.update({
    f"{_SL}forms__mutmut_122": _EINSUM,
    f"{_SL}forms__mutmut_233": _EINSUM,
    f"{_SL}residual__mutmut_49": "reshape(len(Z), -2) infers like -1 (numpy 2.4)",
    f"{_SL}_config__mutmut_8": "a 7th column of the increment, always zero: d6[:, 3:] gains "
                               "a zero 4th entry, which adds 0 to theta^2 and which skew3 "
                               "does not read (it takes components 0 to 2)",
})
_SS = "dynstiff.analyses.sensitivity_statics.xǁLinearisedEquilibriumǁ"
EQUIVALENT.update({
    f"{_SS}derivatives__mutmut_27":
        "check_finite=None for False: a false value, lu_solve skips the check either way",
    f"{_SS}__init____mutmut_26":
        "P['L0'] filled at a fixed pose too: it is read only by quantities() when L0 is no "
        "unknown, i.e. at fixed lengths",
    f"{_SS}__init____mutmut_49": "scale_N = None: the attribute is never read (dead)",
})
_SR = "dynstiff.analyses.sensitivity_rungs.x_"
EQUIVALENT.update({
    f"{_SR}static_forms__mutmut_42": "upper-case einsum subscripts: the same contraction",
    f"{_SR}exact_forms__mutmut_29": "upper-case einsum subscripts: the same contraction",
    f"{_SR}exact_forms__mutmut_59": "upper-case einsum subscripts: the same contraction",
})
_SK = "dynstiff.analyses.sensitivity_kernels.x_"
EQUIVALENT.update({
    f"{_SK}divided_differences__mutmut_14":
        "same-sign test >= 0 for > 0: differs only at Re a or Re b exactly 0, where both iod "
        "forms are exact rearrangements without cancellation (1e-15 apart; unused at delta 0)",
    f"{_SK}mean_tension__mutmut_28":
        "Taylor test <= for <: differs only at W exactly 1e-6 T, where both branches give the "
        "mean tension (the closed form to 1e-10, the series to rounding)",
    f"{_SK}primitives__mutmut_47":
        "dtype=float dropped on a list of Python floats (Cable.EA is a float): float64 anyway",
    f"{_SK}primitives__mutmut_67":
        "dtype=float dropped on Pose.position: Pose stores it as float64 already",
})
_EC = "dynstiff.cable.exact.xǁExactCableǁ"
EQUIVALENT.update({
    f"{_EC}_build_modes__mutmut_152": "argsort kind='STABLE': numpy reads the kind's case "
                                      "insensitively, the same stable sort",
    f"{_EC}_self_check__mutmut_22": "slice(3, None) for slice(3, 6) of a 6 x 6 block: the same",
    f"{_EC}_self_check__mutmut_36":
        "the column blocks (0:3, 0:3) for (0:3, 3:6): the unchecked B-B block's error is the "
        "A-A block's (rigid translations move no force: K_AB = -K_AA, K_BB = K_AA, in the "
        "exact stiffness, and the discrete one to 6e-14 of its largest entry, measured)",
    f"{_EC}_static_floor__mutmut_3": "a 7 x 6 zero array for 6 x 6: its one reader "
                                     "(_self_check) slices rows 0:3 and 3:6 only",
    f"{_EC}_static_floor__mutmut_6": "the floors subtracted, not added: the bound comes out "
                                     "negated, and its one reader takes a 2-norm of it",
})
_DC = "dynstiff.models.dsm_compiled.x_"
_DC_DTYPE = ("numerically the same: the damped kernel computes in complex whatever the input "
             "array's dtype (float where the model's loss factor leaves the values real); "
             "numba only compiles one more specialisation")
EQUIVALENT.update({
    f"{_DC}damped_compiled_arguments__mutmut_44": _DC_DTYPE + " (alpha)",
    f"{_DC}damped_compiled_arguments__mutmut_48": _DC_DTYPE + " (K0)",
    f"{_DC}damped_compiled_arguments__mutmut_52": _DC_DTYPE + " (the assembly map)",
    f"{_DC}damped_compiled_arguments__mutmut_58": "dtype=float dropped on the platform mass "
                                                  "matrix, float64 already",
    f"{_DC}stiffness_and_count__mutmut_21": "dtype=None for float: both callers (sensitivity, "
                                            "participation) pass float arrays of omega",
    f"{_DC}symmetric_assembly__mutmut_11": "reshape(-2, ...) for (-1, ...): numpy takes any "
                                           "negative size as the one unknown (numpy 2.4)",
    f"{_DC}compiled_arguments__mutmut_6": "getattr without a default: its one caller passes "
                                          "a FrequencyModel, which always has _memo",
    f"{_DC}compiled_arguments__mutmut_18": "dtype=None for float on np.real of the float or "
                                           "complex parameters: float64 either way",
    f"{_DC}compiled_arguments__mutmut_20": "dtype dropped on np.real of the float or complex "
                                           "parameters: float64 either way",
    f"{_DC}compiled_arguments__mutmut_36": "dtype=None on K_geo_free, a float64 array already",
    f"{_DC}compiled_arguments__mutmut_40": "dtype=None on the platform mass matrix, float64 "
                                           "already",
    f"{_DC}compiled_arguments__mutmut_42": "dtype dropped on the platform mass matrix, float64 "
                                           "already",
})
_R3 = "dynstiff.report.robot3d.x_"
EQUIVALENT.update({
    f"{_R3}_platform_inset__mutmut_223": "view_init(azim=None) takes the axes' initial azimuth, "
                                         "-60, the default the close-up was made with",
    f"{_R3}_title__mutmut_5": "getattr's default None for '': Robot always has its name field "
                              "(a dataclass field, default ''), the default is never used",
    f"{_R3}_title__mutmut_8": "getattr without a default: Robot always has its name field",
})
_ST = "dynstiff.timedomain.stepping.x_"
EQUIVALENT.update({
    f"{_ST}_kernel_arguments__mutmut_18": "the pose is a FastPose, whose rotation is float64 "
                                          "already: the same copy",
    f"{_ST}_kernel_arguments__mutmut_61": "the K0 placeholder when beta = 0: the kernel reads "
                                          "K0 only if beta != 0 (the same int64 1-D type)",
    f"{_ST}_kernel_arguments__mutmut_71": "astype(None) is astype(float64): the same copy",
    f"{_ST}_kernel_arguments__mutmut_85": "Platform stores its inertia as a float64 array: "
                                          "the same array",
    f"{_ST}compiled_explicit_run__mutmut_46":
        "the table dropped: a table run's excitation callable is np.interp of that same table, "
        "the same loads step by step (test_excitation_table_equals_its_interpolating_callable)",
    f"{_ST}compiled_implicit_run__mutmut_49": "a placeholder LU never solved with: with "
                                              "counters[0][0] = 0 the kernel returns 5 first",
    f"{_ST}finish_compiled_run__mutmut_14": "peaks enter only as their sum (the scale); a "
                                            "compiled run has no winch, peaks 0 and 1 start 0",
    f"{_ST}finish_compiled_run__mutmut_48": "(step, order) pairs built in another order: the "
                                            "tuples sort the same, the lambdas never compared",
})
EQUIVALENT.update({
    "dynstiff.timedomain.simulation.x_simulate__mutmut_427":
        "the table dropped for the callable: a table's excitation callable is np.interp of "
        "that table at the same step times, the same loads bit for bit (only slower)",
})
EQUIVALENT.update({
    "dynstiff.report.document.x_title_rows__mutmut_9":
        "getattr without a default: Scene always has its path field (default None)",
    "dynstiff.report.document.x_platform_mode_table__mutmut_2":
        "or -> and on (no modes, empty index): either way a frame of the same columns and no "
        "row (only the empty columns' dtype differs, which nothing reads)",
})
EQUIVALENT.update({
    "dynstiff.cli.workspace.x__orientations__mutmut_5":
        "np.loadtxt turns dtype=None into float64: the same array as dtype=float",
    "dynstiff.cli.workspace.x__orientations__mutmut_7":
        "np.loadtxt's default comments is '#': the same reading",
    "dynstiff.cli.workspace.x__cmd_workspace__mutmut_132":
        "frf_limit dropped: no --frf-limit option nor scene key sets it, so st.frf_limit is "
        "workspace()'s own default",
    "dynstiff.cli.workspace.x__cmd_workspace__mutmut_231":
        "matplotlib lower-cases backend names: 'agg' is 'Agg'",
})
_RS = "dynstiff.robot.statics.x_"
EQUIVALENT.update({
    f"{_RS}_carried__mutmut_31": "invalid='ignore' dropped around 1 / (1 + cos): it can only "
                                 "divide by zero (cos = -1), never raise invalid",
    f"{_RS}_carried__mutmut_44": "cos >= -0.5 for > -0.5: at cos = -0.5 exactly the row is "
                                 "replaced by u (keep = cos <= -0.5) whatever f is",
    f"{_RS}_carried__mutmut_51": "f = 1 for 0 where cos <= -0.5: those rows are replaced by u",
    f"{_RS}_fixed_point__mutmut_2": "the default of diagnose: its one caller "
                                    "(_inverse_statics) always passes it",
    f"{_RS}_fixed_point__mutmut_5": "the first active set '' for None: np.any('') is False, "
                                    "no guess from it either way",
    f"{_RS}_fixed_point__mutmut_153": "best <= 1e-9 for < 1e-9 in the stall rule: they differ "
                                      "only where the smallest change, a max of float "
                                      "differences, is 1e-9 exactly",
    f"{_RS}_start_or_request__mutmut_24": "least >= t[i] for >: they differ only where the "
                                          "fold's tension (a bounded minimiser's value) "
                                          "equals the relaxed start's exactly",
    f"{_RS}_start_or_request__mutmut_36": "t[i] = None (NaN) for the fold's tension: the "
                                          "start's t is read only by that iteration's change, "
                                          "max(direction change, NaN) is the direction change, "
                                          "then only a first best (far above 1e-9) and the "
                                          "second iteration's last, and the second cannot "
                                          "end the loop, as its "
                                          "distribution moves the tensions the relaxed start "
                                          "had below their limits",
    f"{_RS}_compiled_fixed_point__mutmut_18": "dtype=None on the tension reference, "
                                              "validated to a float array already",
    f"{_RS}_compiled_fixed_point__mutmut_37": "dtype dropped on the anchors, float64 already",
    f"{_RS}_compiled_fixed_point__mutmut_51": "dtype=None on the weight wrench, float64 "
                                              "already",
    f"{_RS}_end_quantities__mutmut_38":
        "a vertical chord's horizontal direction scaled by 2: it enters only as H e_h, and a "
        "vertical cable's H is 0 (the scalar solver's state; tested == 0.0)",
})
EQUIVALENT.update({
    "dynstiff.report.robot.x_robot_report__mutmut_5":
        "matplotlib lower-cases backend names: 'agg' is 'Agg'",
    "dynstiff.report.robot.x_robot_report__mutmut_6":
        "matplotlib lower-cases backend names: 'AGG' is 'Agg'",
    "dynstiff.report.robot.x__page__mutmut_186": "'UTF-8' for 'utf-8': codec names are read "
                                                 "case-insensitively, the same bytes",
})
# eighth round
_CAUGHT = ("the name given to real_array: its error is caught and replaced by "
           "unstretched_lengths' own message, which names the argument")
EQUIVALENT.update({f"dynstiff._validate.x_unstretched_lengths__mutmut_{n}": _CAUGHT
                   for n in (12, 13)})
EQUIVALENT.update({
    "dynstiff.report.geometry3d.x__geometry__mutmut_18":
        "dtype=float dropped on the pose's position, which Pose stores as float64",
    "dynstiff.report.geometry3d.x__hull__mutmut_83":
        "a Qhull facet equation times its normal's norm instead of divided by it: Qhull's "
        "normals are unit vectors, so the two differ by an ulp, far inside the 1 degree and "
        "1 % tolerances of the coplanar test",
})
EQUIVALENT.update({
    "dynstiff.robot.statics.x__compiled_fixed_point__mutmut_87":
        "range(3) attempts instead of 2: the second attempt breaks (attempt is truthy) "
        "unless it returned, so a third is never reached",
    "dynstiff.robot.statics.x__compiled_fixed_point__mutmut_57":
        "dtype=float dropped on EA, already float64 (Cable stores floats)",
    "dynstiff.robot.statics.x__inverse_statics__mutmut_87":
        "the kernel's catenaries started cold instead of from the start's: the same outer "
        "iterations (7 for CoGiRo moved 0.37 m, measured) to the same lengths to rounding; "
        "only the inner Newton's work differs",
    "dynstiff.robot.statics.x__step_distribution__mutmut_38":
        "t_max + hi for t_max - hi in the straight chords' relaxed distribution: straight "
        "holds only for a cold start's first distribution, whose hi is zeros",
})
EQUIVALENT.update({f"dynstiff.cli.report.x__cmd_demo__mutmut_{n}":
                   "info(None) for info(args): demo has no --csv or --json, so its report "
                   "goes to standard output either way" for n in (47, 49)})
EQUIVALENT.update({
    "dynstiff.analyses.calibrate.x_calibrate__mutmut_149":
        "H_meas is read only when frf is given, and then set to frf.H first",
    "dynstiff.analyses.calibrate.x_calibrate__mutmut_363":
        "u is always a float64 array (scipy's x, x +- h e, sol.x): the same copy",
    "dynstiff.analyses.calibrate.x_calibrate__mutmut_436":
        "unreachable: scipy's trf calls jac(x) right after fun(x), so r0 is the last residual",
    "dynstiff.analyses.calibrate.x_calibrate__mutmut_499":
        "unreachable: trf refuses a non-finite start and takes no non-finite step, so "
        "r(sol.x) is finite",
})
EQUIVALENT.update({
    **{f"dynstiff.analyses.damped.x__shape_owner__mutmut_{n}":
       "a strict comparison of a MAC with 0.9 or 0.5 made inclusive: differs only at "
       "exactly equal floats" for n in (40, 47)},
    "dynstiff.analyses.damped.x_damped_modes__mutmut_153":
        "the owner stored for a multiple root's copy is never read: a later root at that "
        "frequency finds the original first (same[0] is the earliest found root)",
})
EQUIVALENT.update({
    "dynstiff.analyses.compare_lumped.x_compare_modes__mutmut_176": "1e+300 is the same float "
                                                                    "as 1e300",
    "dynstiff.analyses.compare_lumped.x_compare_modes__mutmut_154":
        "the frequency pairing run with one side empty: a (0, k) or (k, 0) cost matrix, "
        "where linear_sum_assignment pairs nothing",
    **{f"dynstiff.cli.simulate.x__cmd_simulate__mutmut_{n}":
       "matplotlib.use('agg') or 'AGG' for 'Agg': backend names are case-insensitive"
       for n in (303, 304)},
})
EQUIVALENT.update({
    "dynstiff.cli.sweep.x_add_parsers__mutmut_114":
        "add_pose(lengths=None) for False: add_pose tests its truth only",
    "dynstiff.cli.sweep.x__cmd_sweep__mutmut_266":
        "the legend's loc 'best' for 'upper left' at the point (1.01, 1): it is drawn for "
        "--trajectory only, whose sweep ends at the last waypoint, drawn full height; 'best' "
        "tries upper right first (the legend over the axes' right edge, which that line "
        "crosses), then upper left (outside the axes, empty): the same place",
    "dynstiff.cli.sweep.x__cmd_sweep__mutmut_230":
        "matplotlib.use('agg') for 'Agg': backend names are case-insensitive",
})
EQUIVALENT.update({
    "dynstiff.analyses.eigen.x__seed_grid__mutmut_37":
        "pts >= 0 for pts > 0: pts never holds 0 (linspace[1:] > 0, w0 > 0 by its filter), "
        "and 0.0 is prepended and merged by np.unique",
    "dynstiff.analyses.eigen.x__counter__mutmut_90":
        "errstate(invalid=None): eigvalsh sets its own errstate, and K + K.T is invalid only "
        "for K_ij = -K_ji = inf, which no rung's symmetric assembly gives",
    "dynstiff.analyses.eigen.x_eigenfrequencies__mutmut_142":
        "w_hi >= 1e8 for > 1e8: w_hi = min(2 pi 2^k, max_omega) is 1e8 only for a model whose "
        "band ends exactly at 1e8 rad/s (16 MHz), which no rung is built to",
})
EQUIVALENT.update({f"dynstiff.analyses.measured.xǁMeasuredModesǁ__post_init____mutmut_{n}":
                   "the name given to real_array: its error is caught and replaced by "
                   "MeasuredModes' own message, which names freq_hz" for n in (7, 8)})
_MFRF = "dynstiff.analyses.measured_frf.x_read_measured_frf__mutmut_"
EQUIVALENT.update({
    **{f"{_MFRF}{n}": "None for 0 as the default of a record's abscissa type: pyuff's reader "
                      "gives every type 58 record its abscissa type" for n in (70, 73)},
    f"{_MFRF}167": "'XXXX' for '' as the default id1 in a message: pyuff's reader gives every "
                   "record an id1 ('NONE' when the file has none)",
    f"{_MFRF}103": "dtype=float dropped on the abscissa: pyuff gives it as float64",
})
EQUIVALENT.update({
    **{f"dynstiff.analyses.participation.x_modal_data__mutmut_{n}":
       "massless= not passed to massless_pairing, which then runs the same eigh(sym K0, "
       "M_p) as massless_modes" for n in (79, 84)},
    "dynstiff.analyses.participation.x_modal_data__mutmut_30":
        "< for <= in the coincident-roots test: differs only for a gap of exactly 1e-8 f",
    "dynstiff.plot.frf.x_plot_frf__mutmut_341":
        "grid(None, alpha=...): matplotlib turns the grid on when line properties are given",
})
EQUIVALENT.update({
    "dynstiff.analyses.settings.x_analysis_settings__mutmut_28":
        "checked_band without its name argument: its default name is 'band_hz'",
    **{f"dynstiff.analyses.settings.x_analysis_settings__mutmut_{n}":
       f"getattr(scene, '{field}') without its default None: every Scene has the field"
       for n, field in ((64, "model"), (89, "segments"))},
    "dynstiff.analyses.sensitivity.x_sensitivities_at__mutmut_96":
        "array_equal(None, Xb) is False: the fields of Xb are computed again when Xb equals "
        "Xa, the same values (exact_fields is a pure function of its arguments)",
    **{f"dynstiff.plot.modes.x_plot_tensions__mutmut_{n}":
       "dtype=float dropped on tensions that an Equilibrium or LumpedEquilibrium holds as "
       "float64 already" for n in (38, 45)},
    "dynstiff.plot.sweep.x_plot_veering__mutmut_145": "matplotlib colour names ignore case",
    "dynstiff.plot.sweep.x_plot_veering__mutmut_64":
        "n = 10: tab10(t / 9) falls in tab10's bin t, the colour tab10(t)",
    "dynstiff.plot.sweep.x_plot_veering__mutmut_214":
        "Axis.grid given keyword arguments and no flag turns the grid on",
    "dynstiff.plot.sweep.x_plot_veering__mutmut_136":
        "default track -1 or -2: both < 0, every mode untracked",
})
EQUIVALENT["dynstiff.plot.workspace.x_plot_workspace_slices__mutmut_43"] = (
    "squeeze=None for False: matplotlib tests its truth only, and keeps the 2-D array")
EQUIVALENT.update({
    "dynstiff.analyses.uncertainty.xǁUncertainǁ__post_init____mutmut_8":
        "the name only words positive_scalar's message, which the except replaces by its own",
    "dynstiff.cable.catenary.x_catenary_states__mutmut_3":
        "dtype=float dropped on anchors that are float64 (the statics pass the robot's)",
    "dynstiff.cable.catenary.x_catenary_states__mutmut_38":
        "the safe fill reaches only the rows of E, F of cables not clear, which are never read",
    "dynstiff.models.dsm_guard.x_static_error__mutmut_8":
        "the type named in typing.cast: cast returns its value unchanged at run time",
    "dynstiff.robot.waypoints.xǁWaypointPathǁ__post_init____mutmut_69":
        "required=None for False: _rows tests its truth only",
})
_CMP = "dynstiff.analyses.compare_lumped.x_compare_modes__mutmut_"
EQUIVALENT.update({
    **{f"{_CMP}{n}": _EINSUM for n in (70, 81)},
    f"{_CMP}52": "a strict comparison made inclusive: differs only at exactly equal floats",
    f"{_CMP}132": "pairs = [...] for pairs += [...]: pairs is still the empty list there",
    f"{_CMP}198": "the upper clip 1.0 of 1 - c / c' dropped: the costs are >= 0, so the value "
                  "never exceeds 1",
    "dynstiff.analyses.eigen.x_eigenfrequencies__mutmut_141":
        "the band grown by 3 instead of 2 until it holds n_modes: the same lowest n_modes are "
        "found in the larger band (Wittrick-Williams counts every one below it)",
})
_SA = "dynstiff.analyses.sensitivity."
_SECANT = ("the secant's second starting point moved by another 1e-6 of the estimate: it "
           "converges to the same root, to its tolerance (1e-12 relative)")
EQUIVALENT.update({
    "dynstiff.cable.dsm_fields.x_field_kinetic_energies__mutmut_12":
        "omega not made float for stacked parameters: the model passes float arrays, and an "
        "integer one would be made float by its first product with a float parameter",
    "dynstiff.analyses.modes.x_modes__mutmut_108":
        "eigh of the empty stack when no root's K is finite: empty arrays, and the loop "
        "over no clusters does nothing",
    "dynstiff.analyses.modes.x_modes__mutmut_131":
        "< for <= in the count of K's null eigenvalues at a root on a cable pole: differs "
        "only for an eigenvalue of exactly 1e-6 of the scale (tested at 0.5 and 2 times it)",
    "dynstiff.analyses.modes.x_modes__mutmut_25":
        ">= for > in the matrix path's limit check: with n_dof equal to max_modes every "
        "request fits (a discrete rung has n_dof modes), so the extra call passes, unused",
    f"{_SA}x__null_vectors__mutmut_18": "dtype=int dropped on an array of Python ints",
    f"{_SA}x__null_vectors__mutmut_23":
        "the points beside a root swapped (w / (1 -+ 1e-9) for w (1 -+ 1e-9)): only "
        "whether the counts there are equal is read",
    f"{_SA}x_sensitivities_at__mutmut_15":
        "dtype=None: frequencies given as integers become float in 2 pi f",
    f"{_SA}x_sensitivities_at__mutmut_142": _EINSUM,
    f"{_SA}x_sensitivities_at__mutmut_50":
        "pairs (a, b) with a > b too, and of modes at rest: a cluster's (b, a) entry is "
        "its (a, b) entry again (x_a^T dK x_b of a symmetric dK, symmetrised anyway), and "
        "the modes at rest are skipped in the assembly",
    "dynstiff.analyses.sensitivity_result.xǁSensitivityResultǁplot__mutmut_9":
        "squeeze=None for False: falsy all the same (an array of axes either way)",
    "dynstiff.analyses.sensitivity_result.xǁSensitivityResultǁplot__mutmut_53":
        "'TAB:RED' for 'tab:red': matplotlib's colour names are case-insensitive",
    "dynstiff.analyses.sensitivity_result.xǁSensitivityResultǁplot__mutmut_62":
        "axvline() for axvline(0.0): x = 0 is its default",
    **{f"dynstiff.analyses.damped.x_damped_modes__mutmut_{n}": _SECANT for n in (73, 78, 79)},
    "dynstiff.analyses.damped.x_damped_modes__mutmut_103":
        "< for <= in the secant's stopping test: differs only for a step of exactly tol",
    "dynstiff.analyses.damped.x_damped_modes__mutmut_180":
        "<= for < against the other modes' estimates: a tie, at exactly equal distance from "
        "two modes' estimates, is all it changes (a copy's own twin is no longer among them)",
})
EQUIVALENT = _relocated(EQUIVALENT)

#: The judged code of each equivalent mutant ({name: sha1 of its mutated function, name
#: left out}), written by ``--stamp``: a mutant number counts within its function, so an
#: edit of the function gives the number to another mutant, and the judgement no longer
#: applies. An equivalent whose code differs from its stamp (or that has none) counts as a
#: survivor and is listed to be judged again.
STAMPS_FILE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "mutation_stamps.json")


def _load_stamps():
    import json
    if not os.path.exists(STAMPS_FILE):
        return {}
    with open(STAMPS_FILE, encoding="utf-8") as fh:
        return json.load(fh)


_SOURCES = {}


def _mutant_code(name):
    """The source of mutant ``name`` as mutmut wrote it (mutants/), its name replaced by
    MUTANT; None when it is not there."""
    module, func = re.match(r"(dynstiff\.[\w.]+?)\.(x.*)$", name).groups()
    path = os.path.join("mutants", *module.split(".")) + ".py"
    if not os.path.exists(path):
        path = os.path.join("mutants", *module.split("."), "__init__.py")
    if path not in _SOURCES:
        if not os.path.exists(path):
            return None
        with open(path, encoding="utf-8") as fh:
            _SOURCES[path] = fh.read().splitlines()
    lines = _SOURCES[path]
    head = re.compile(r"^(\s*)def " + re.escape(func) + r"\(")
    for i, line in enumerate(lines):
        m = head.match(line)
        if m:
            indent = len(m.group(1))
            body = [line.replace(func, "MUTANT", 1)]
            for nxt in lines[i + 1:]:
                if nxt.strip() and len(nxt) - len(nxt.lstrip()) <= indent:
                    break
                body.append(nxt)
            return "\n".join(body).rstrip()
    return None


def _stamp(name):
    import hashlib
    code = _mutant_code(name)
    return None if code is None else hashlib.sha1(code.encode()).hexdigest()[:16]


def _stale_equivalents(names, stamps):
    """The equivalent mutants among ``names`` whose judged code is not theirs today."""
    return {n for n in names if n in EQUIVALENT and (n not in stamps
                                                      or stamps[n] != _stamp(n))}


def _write_stamps():
    """Stamp every equivalent mutant not stamped yet whose module's mutants were written from
    this tree's source (the module of mutants/ equals the package's own file)."""
    import json
    import pathlib
    root = pathlib.Path(__file__).resolve().parents[1]
    stamps = _load_stamps()
    added, skipped = [], []
    for name in EQUIVALENT:
        if name in stamps:
            continue
        module = _module(name)
        rel = pathlib.Path(*module.split(".")).with_suffix(".py")
        if not (root / rel).exists():
            rel = pathlib.Path(*module.split("."), "__init__.py")
        if not rel.exists() or rel.read_bytes() != (root / rel).read_bytes():  # this tree's
            skipped.append(name)
            continue
        st = _stamp(name)
        if st is None:
            skipped.append(name)
            continue
        stamps[name] = st
        added.append(name)
    with open(STAMPS_FILE, "w", encoding="utf-8") as fh:
        json.dump(dict(sorted(stamps.items())), fh, indent=0)
        fh.write("\n")
    print(f"stamped {len(added)} equivalent mutants; {len(skipped)} not stamped (their "
          f"module differs from this tree's, or the mutant is not written)")
    for name in skipped:
        print(f"  not stamped: {name}")


def _results():
    """{mutant name: status} of every generated mutant (mutmut's last results)."""
    out = subprocess.run(["mutmut", "results", "--all", "true"], capture_output=True,
                         text=True).stdout
    res = {}
    for line in out.splitlines():
        m = re.match(r"\s*(dynstiff\.\S+__mutmut_\d+): (.+)$", line)
        if m:
            res[m.group(1)] = m.group(2).strip()
    return res


#: mutmut's command line, its check that a forced failure fails the tests made to accept a
#: failed conftest import: tests/conftest.py builds cables at import, so the forced failure
#: (every trampoline raising) stops the run there, which pytest reports as a usage error.
_MUTMUT = """
import sys
import mutmut.__main__ as m
from mutmut.runners.harness import BadTestExecutionCommandsException

forced_fail = m.run_forced_fail_test


def run_forced_fail_test(runner):
    try:
        forced_fail(runner)
    except BadTestExecutionCommandsException:
        pass


m.run_forced_fail_test = run_forced_fail_test
sys.argv = ["mutmut"] + sys.argv[1:]
m.cli()
"""


def _durations():
    """{mutant name: seconds its tests took} of every judged mutant (mutmut's .meta files):
    with one child, a module's wall time is their sum (the per-run overhead apart)."""
    import json
    import pathlib
    out = {}
    for meta in pathlib.Path("mutants").rglob("*.py.meta"):
        out.update(json.loads(meta.read_text()).get("durations_by_key", {}))
    return out


def _generate():
    """Write every module's mutants (mutants/), without running any test: the sample is
    drawn from them. One process (the machine is shared)."""
    code = ("import os; from mutmut.__main__ import copy_src_dir, copy_also_copy_files, "
            "setup_source_paths, create_mutants; os.makedirs('mutants', exist_ok=True); "
            "copy_src_dir(); copy_also_copy_files(); setup_source_paths(); create_mutants(1)")
    subprocess.run([sys.executable, "-c", code], check=True, stdout=subprocess.DEVNULL)


def _module(name):
    return re.match(r"(dynstiff\.[\w.]+?)\.x", name).group(1)


def _verdict(name, status, stale=frozenset()):
    """killed / survived / equivalent / unchecked: a timeout or a crash is a detection, a
    mutant that no test reaches is a survivor, an equivalent whose code changed since its
    judgement (``stale``) too."""
    if status in ("killed", "timeout", "segfault"):
        return "killed"
    if status in ("survived", "no tests"):
        return "equivalent" if name in EQUIVALENT and name not in stale else "survived"
    return "unchecked"


def _sample(names, size, seed, chunk=100):
    """A seeded uniform sample of ``size`` mutants per module, drawn without replacement in
    rounds of ``chunk`` from the mutants not drawn yet (a partial last round takes the first
    of a whole round's draw), so a larger sample contains the smaller one (the judged mutants
    are reused) and stays uniform. Each module has its own generator, seeded by ``seed`` and
    the module's name: its sample does not depend on which other modules exist."""
    pools = collections.defaultdict(list)
    for n in names:
        pools[_module(n)].append(n)
    drawn = []
    for mod, pool in sorted(pools.items()):
        rng = np.random.default_rng([seed, zlib.crc32(mod.encode())])
        pool = sorted(pool)
        for start in range(0, size, chunk):
            if not pool:
                break
            pick = rng.choice(pool, min(chunk, len(pool)), replace=False)
            drawn.extend(pick[:size - start])
            pool = sorted(set(pool) - set(pick))
    return drawn


def _wilson(k, n, z=1.96):
    """95 % Wilson interval of a proportion k / n."""
    if n == 0:
        return float("nan"), float("nan")
    p = k / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * np.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    return centre - half, centre + half


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("modules", nargs="*", help="e.g. dynstiff/analyses/frf.py (default: all)")
    ap.add_argument("--report-only", action="store_true", help="print the last results")
    ap.add_argument("--sample", type=int, default=0,
                    help="judge a uniform random sample of this many mutants per module "
                         "(score with its 95 %% interval) instead of every mutant")
    ap.add_argument("--seed", type=int, default=20261202)
    ap.add_argument("--recheck", action="store_true",
                    help="run the surviving mutants again too (after tests were added)")
    ap.add_argument("--restat", action="store_true",
                    help="collect again which tests reach each function (after code moved)")
    ap.add_argument("--children", type=int, default=1,
                    help="mutmut's parallel children (default 1: the machine is shared)")
    ap.add_argument("--stamp", action="store_true",
                    help="stamp the equivalent mutants not stamped yet with their code "
                         "(after judging them), then stop")
    args = ap.parse_args(argv)
    if args.stamp:
        _write_stamps()
        return
    prefixes = [m[:-3].replace("/", ".").removesuffix(".__init__") + ".x"
                for m in args.modules]
    t0 = time.perf_counter()
    if args.restat and os.path.exists(os.path.join("mutants", "mutmut-stats.json")):
        os.remove(os.path.join("mutants", "mutmut-stats.json"))
    res = _results()
    if not res:
        _generate()
        res = _results()
    names = list(res)
    if args.sample:
        names = _sample(names, args.sample, args.seed)
    names = [n for n in names if not prefixes or n.startswith(tuple(prefixes))]
    if not args.report_only:
        redo = ("unchecked", "survived") if args.recheck else ("unchecked",)
        stale = _stale_equivalents(names, _load_stamps())
        todo = [n for n in names if _verdict(n, res[n], stale) in redo]
        for k in range(0, len(todo), 2000):         # one mutmut call per 2000 names
            subprocess.run([sys.executable, "-c", _MUTMUT, "run", "--max-children",
                            str(args.children)]
                           + todo[k:k + 2000], check=False,
                           env=dict(os.environ, HYPOTHESIS_PROFILE="mutation"))
        res = _results()
        # a module edited since the sample was drawn has new mutants: the names gone are
        # left out (the next run samples the new ones)
        names = [n for n in names if n in res]
    wall = time.perf_counter() - t0
    took = _durations()
    _SOURCES.clear()                    # the run may have written a module's mutants again
    stale = _stale_equivalents(names, _load_stamps())
    status = collections.defaultdict(collections.Counter)
    seconds = collections.Counter()
    survivors = []
    for n in names:
        v = _verdict(n, res[n], stale)
        status[_module(n)][v] += 1
        seconds[_module(n)] += took.get(n, 0.0)
        if v == "survived":
            survivors.append(n)
    kind = f"sample of {args.sample} per module" if args.sample else "all mutants"
    print(f"mutation score ({kind}; equivalent mutants excluded)")
    print(f"{'module':<34s} {'mutants':>7s} {'killed':>6s} {'survived':>8s} "
          f"{'equivalent':>10s} {'unchecked':>9s} {'score':>6s} {'tests':>7s}"
          + ("  95 % interval" if args.sample else ""))
    total = collections.Counter()
    for module, c in sorted(status.items()):
        total.update(c)
        judged = c["killed"] + c["survived"]
        lo, hi = _wilson(c["killed"], judged)
        score = c["killed"] / judged if judged else float("nan")
        print(f"{module:<34s} {sum(c.values()):7d} {c['killed']:6d} {c['survived']:8d} "
              f"{c['equivalent']:10d} {c['unchecked']:9d} {score:6.1%} "
              f"{seconds[module] / 60:5.1f}mn"
              + (f"  [{lo:.1%}, {hi:.1%}]" if args.sample else ""))
    judged = total["killed"] + total["survived"]
    if judged:
        print(f"{'all':<34s} {sum(total.values()):7d} {total['killed']:6d} "
              f"{total['survived']:8d} {total['equivalent']:10d} {total['unchecked']:9d} "
              f"{total['killed'] / judged:6.1%}")
    if not prefixes:
        print(f"\nmodules without mutants: {', '.join(_without_mutants(res))}")
    print(f"\nrun time {wall / 60:.1f} min (tests: the time of the mutants' tests); "
          f"surviving mutants ({len(survivors)}):")
    for name in survivors:
        print(f"  {name}   (mutmut show {name})"
              + ("   [listed as equivalent, its code changed: judge again]"
                 if name in stale else ""))


def _without_mutants(res):
    """The modules of the package mutmut wrote no mutant for (NO_MUTANTS says why)."""
    import pathlib
    root = pathlib.Path(__file__).resolve().parents[1]
    have = {_module(n) for n in res}
    out = []
    for path in sorted((root / "dynstiff").rglob("*.py")):
        module = ".".join(path.relative_to(root).with_suffix("").parts)
        if module.removesuffix(".__init__") not in have:
            out.append(module)
    return out

if __name__ == "__main__":
    main(sys.argv[1:])
