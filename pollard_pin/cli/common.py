"""What the commands share: argument types that reject what the API would reject (before any
work), the model/trajectory options, loading the model and the trajectory, progress bars."""
from __future__ import annotations

import argparse
import contextlib
import logging
import math
import re
import sys
import time
import warnings
from pathlib import Path

from ..checks import EXAMPLE_ADDRESS, address_problem, is_integer, problem, shorten
from ..errors import InputError
from ..io.atomic import STDOUT
from ..model.values import parse_float, parse_int

log = logging.getLogger("pollard_pin")


class UsageError(InputError):
    """A command-line value the command cannot use (one line)."""


# a value, not an option: "-" then a digit, ".digit", inf or nan (no option is named so):
# "-1e-3", "-inf", the comma lists "-10,0,0" and "-0.1,0.2", and typos such as "-1x", which
# the option's own check then names
NEGATIVE_NUMBER = re.compile(r"^-(\.?\d|inf(inity)?\b|nan\b)", re.I)


@contextlib.contextmanager
def as_flags(owner: str):
    """An InputError naming a field of ``owner`` (``PlannerPolicy.seam_run = 1e+300: …``)
    said as the flag that set it (``--seam-run 1e+300: …``): the user typed the flag. Only
    around the options' construction, where each field is a flag's."""
    try:
        yield
    except InputError as exc:
        said = re.sub(rf"\b{owner}\.(\w+)(\[\d+\])?( = )?",
                      lambda m: f"--{m[1].replace('_', '-')}{' ' if m[3] else ''}", str(exc))
        raise UsageError(said) from None


class Parser(argparse.ArgumentParser):
    """argparse with one-line errors (no usage block): ``pollard-pin run: error: ...``."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        # "-1e-3", "-inf" and "-10,0,0" are values, so that their own check speaks, not
        # "expected one argument" (argparse's own pattern knows only -1 and -.5)
        self._negative_number_matcher = NEGATIVE_NUMBER

    def error(self, message: str):
        self.exit(2, f"{self.prog}: error: {message}\n")


class HelpFormatter(argparse.ArgumentDefaultsHelpFormatter, argparse.RawDescriptionHelpFormatter):
    """Every default in --help: shown by argparse, or said in the help text where the default
    is "none given" (then the text says what happens)."""

    def _get_help_string(self, action):
        if action.default in (None, [], False, argparse.SUPPRESS):
            return action.help
        return super()._get_help_string(action)


# --- argument types: each rejects what the API would reject, before any work ----------------
def number(text: str) -> float:
    try:
        value = parse_float(text)
    except ValueError as exc:
        why = "" if "float" in str(exc) else f" ({exc})"  # float()'s own: no news
        raise argparse.ArgumentTypeError(f"not a number: {shorten(text)}{why}") from None
    return _ruled(value, text)


def _ruled(value: float, text: str, low: float = -math.inf, high: float = math.inf,
           above: bool = False) -> float:
    """``value`` under the one value rule (:func:`pollard_pin.checks.problem`)."""
    wrong = problem(value, low, high, above)
    if wrong is not None:
        # as typed if short; else the value, or the text shortened if it overflowed
        shown = (text.strip() if len(text) <= 30 else
                 f"{value:.4g}" if math.isfinite(value) else shorten(text))
        raise argparse.ArgumentTypeError(f"{wrong}, got {shown}")
    return value


def positive(text: str) -> float:
    return _ruled(number(text), text, 0.0, above=True)


def nonnegative(text: str) -> float:
    return _ruled(number(text), text, 0.0)


def numbers(text: str) -> tuple[float, ...]:
    """Comma-separated numbers (e.g. a cell's seams, 0.092,0.159)."""
    return tuple(number(t) for t in text.split(","))


def fraction(text: str) -> float:
    """A number in [0, 1] (e.g. a margin on |sin θ|)."""
    return _ruled(number(text), text, 0.0, 1.0)


def name(text: str) -> str:
    """A file or folder name: not empty (an empty name would mean the current folder)."""
    if not text:
        raise argparse.ArgumentTypeError("an empty name; give a file or folder name")
    return text


def scheduler_address(text: str) -> str:
    """A Dask scheduler's address, not empty (no --dask is the local pool), and well formed
    (:func:`pollard_pin.checks.address_problem`, the API's rule too): a typo is refused here,
    not after the work that comes before connecting."""
    wrong = address_problem(text)
    if wrong is not None:
        raise argparse.ArgumentTypeError(f"{wrong}; e.g. {EXAMPLE_ADDRESS}")
    return text.strip()


def count(minimum: int, maximum: int | None = None):
    def parse(text: str) -> int:
        digits = text.strip().lstrip("+")
        if digits.isascii() and digits.isdigit() and len(digits) > 30:
            bound = f"between {minimum} and {maximum}" if maximum else f"a sane count >= {minimum}"
            raise argparse.ArgumentTypeError(f"must be {bound}, got a {len(digits)}-digit number")
        try:
            value = parse_int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"not an integer: {shorten(text)}") from None
        if not is_integer(value, minimum, maximum):
            bound = f"between {minimum} and {maximum}" if maximum else f">= {minimum}"
            raise argparse.ArgumentTypeError(f"must be {bound}, got {text}")
        return value

    return parse


# --- shared steps ---------------------------------------------------------------------------
def progress(label: str, enabled: bool):
    """A tqdm bar fed by the pipeline's ``progress(done, total)`` calls; silent when not on a
    terminal (tqdm's ``disable=None``) or with --quiet."""
    if not enabled:
        return None
    from tqdm import tqdm

    state = {}

    def report(done: int, total: int) -> None:
        bar = state.get("bar")
        if bar is None:
            bar = state["bar"] = tqdm(total=total, desc=label, unit="sample", disable=None,
                                      leave=False, file=sys.stderr)
        bar.update(done - bar.n)
        if done >= total:
            bar.close()

    return report


def params_of(args):
    """The parameters of --params (a file, possibly partial) and --set, or None (shipped)."""
    from ..model.overrides import parse_assignment
    from ..model.params import ParameterError, load_params

    try:
        sets = dict(parse_assignment(s) for s in getattr(args, "set", None) or ())
    except ParameterError as exc:  # the library speaks of the override; name the flag
        raise ParameterError(f"--set: {exc}") from None
    if args.params is None and not sets:
        return None
    return load_params(args.params, overrides=sets)


def load_robot(args):
    from ..model.build import load

    t0 = time.perf_counter()
    robot = load(params_of(args))
    log.info("model %s loaded in %.1f ms", robot.params.source, 1e3 * (time.perf_counter() - t0))
    return robot


def load_trajectory(args, params, lazy: bool = False):
    """The chosen trajectory; ``lazy``: the thesis curve evaluated window by window (run)."""
    from ..io.trajectory import from_csv
    from ..paths.curves import THESIS_DURATION, THESIS_SAMPLES, ThesisTrajectory, thesis_trajectory

    if args.trajectory == "thesis":
        duration = THESIS_DURATION if args.duration is None else args.duration
        samples = THESIS_SAMPLES if args.samples is None else args.samples
        make = ThesisTrajectory if lazy else thesis_trajectory
        return make(duration=duration, samples=samples, home_pose=params.home_pose)
    if args.duration is not None or args.samples is not None:
        args.notes.append("--duration/--samples apply to the thesis trajectory only; the CSV "
                          "file's own times are used")
    with warnings_as_notes(args):
        return from_csv(args.trajectory)


def robot_for_trajectory(args, robot):
    """The robot with the gravity the trajectory CSV's metadata records (a paint cell's turned
    robot, docs/model.md §26.1; a note says it), else itself (gravity (0, 0, −9.81))."""
    import numpy as np

    from ..io.trajectory import trajectory_gravity
    from ..model.gravity import with_gravity

    if getattr(args, "trajectory", "thesis") == "thesis":
        return robot
    g = trajectory_gravity(args.trajectory)
    if g is None or np.array_equal(g, np.asarray(robot.model.gravity.linear)):
        return robot
    shown = ", ".join(f"{c:.6g}" for c in np.round(g, 9) + 0.0)  # no −1e-15 round-off
    args.notes.append(f"gravity ({shown}) m/s² in the robot's "
                      f"base frame, from {args.trajectory}'s metadata")
    return with_gravity(robot, g)


@contextlib.contextmanager
def warnings_as_notes(args):
    """The library's warnings become notes, said once the command has succeeded (an error is
    then the only line)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        yield
    args.notes.extend(str(w.message) for w in caught)


def say_notes(args) -> None:
    """Print the notes gathered so far, each once, in order."""
    for note in dict.fromkeys(args.notes):
        print(f"note: {note}", file=sys.stderr)
    args.notes.clear()


def solve(args, dynamics: bool = True, **ik_options):
    """Load the model and the chosen trajectory, run the pipeline (run/view/plot/report)."""
    from ..run import run_pipeline

    robot = load_robot(args)
    traj = load_trajectory(args, robot.params)
    robot = robot_for_trajectory(args, robot)
    log.info("trajectory %s: %d samples over %.4g s (derivatives: %s)", traj.name, len(traj),
             traj.t[-1] - traj.t[0], traj.derivatives)
    t0 = time.perf_counter()
    result = run_pipeline(robot, traj, dynamics=dynamics,
                          progress=progress("solving", len(traj) >= 500 and not args.quiet),
                          joint_limits=not args.ignore_limits, **ik_options)
    log.info("solved in %.3f s", time.perf_counter() - t0)
    return robot, result


def wrote(path, what: str = "") -> None:
    if str(path) != STDOUT:
        print(f"wrote {path}{what}", file=sys.stderr)


def simulation_table(path):
    """The columns and metadata of a ``simulate`` table (one-line error otherwise)."""
    from ..io.table import read_result
    from ..viz.simulation import check_simulation_columns

    table = read_result(path)
    check_simulation_columns(table.columns, str(path))
    return table


def margin_args(p) -> None:
    """--wrist-margin and --singularity-margin (docs/model.md §12), for :func:`margins_of`."""
    from ..kinematics.margins import SINGULARITY_MARGIN, WRIST_MARGIN

    p.add_argument("--wrist-margin", type=fraction, default=WRIST_MARGIN,
                   help="smallest |sin θ1716| allowed: a pose below it fails (equal passes)")
    p.add_argument("--singularity-margin", type=nonnegative, default=SINGULARITY_MARGIN,
                   help="smallest parallel and serial σ_min allowed: a pose below it fails "
                        "(equal passes)")


def margins_of(args):
    """The :class:`~pollard_pin.kinematics.margins.Margins` of the flags, built once."""
    from ..kinematics.margins import MarginError, Margins

    try:
        return Margins(args.wrist_margin, args.singularity_margin)
    except MarginError as exc:  # the library speaks of the value; name the flag
        flag = "--wrist-margin" if str(exc).startswith("wrist") else "--singularity-margin"
        raise UsageError(f"{flag}: {exc}") from None


def command(sub, parents, name: str, help: str, run):
    """The subparser of one command, running ``run(args)``."""
    p = sub.add_parser(name, help=help, description=help, parents=parents,
                       formatter_class=HelpFormatter)
    p.set_defaults(func=run)
    return p


def model_args(p) -> None:
    p.add_argument("--params", type=name, metavar="FILE.toml", default=None,
                   help="parameter file; may list only the values that differ from the "
                        "shipped models/pollard.toml (default: the shipped parameters)")
    p.add_argument("--set", metavar="KEY=VALUE", action="append", default=[],
                   help="override one parameter, e.g. chain0.x32=0.35 (repeatable; "
                        "units as in the parameter file; default: none)")


def trajectory_args(p) -> None:
    model_args(p)
    p.add_argument("--trajectory", type=name, metavar="thesis|FILE.csv", default="thesis",
                   help="the thesis painting curve or a trajectory CSV")
    p.add_argument("--duration", type=positive, default=None, metavar="S",
                   help="thesis trajectory duration [s] (default: 20)")
    p.add_argument("--samples", type=count(2), default=None, metavar="N",
                   help="thesis trajectory samples (default: 2001)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.add_argument("--ignore-limits", action="store_true",
                   help="solve poses with joints outside the parameter file's [limits] "
                        "(default: refuse them, like workspace and paint)")


def command_inputs(args) -> list:
    """(what, path) of the files a command reads through the shared options: the parameter
    file, a trajectory CSV and its units sidecar, the actuators, a sweep grid, a simulation
    table."""
    from ..io.table import units_path

    files = [("the parameter file", getattr(args, "params", None)),
             ("the actuators", getattr(args, "actuators", None)),
             ("the sweep grid", getattr(args, "grid", None)),
             ("the simulation table", getattr(args, "simulation", None))]
    traj = getattr(args, "trajectory", None)
    if traj not in (None, "thesis"):
        files += [("the trajectory", traj), ("the trajectory's units", units_path(traj))]
    return [(what, path) for what, path in files if isinstance(path, (str, Path))]


def refuse_inputs(args, *outputs, also=()) -> None:
    """An output that is one of the command's inputs (:func:`command_inputs`, and ``also``:
    the command's own (what, path) pairs) is refused before any work (one line): writing it
    would destroy what is read."""
    from ..io.atomic import check_not_inputs

    check_not_inputs([o for o in outputs if o is not None], [*command_inputs(args), *also])
