"""pollard-pin design: search link lengths, joint ranges, motors and the number of robots for
the robots that paint a job (docs/model.md §31); a thin layer over
:func:`pollard_pin.synthesis.api.design`."""
from __future__ import annotations

import contextlib
import os
import signal
import sys
from pathlib import Path

from ..checks import SEEDS
from .common import (
    command,
    count,
    name,
    refuse_inputs,
    scheduler_address,
    warnings_as_notes,
    wrote,
)

OUTPUTS = ("params.toml", "actuators.toml", "robots.toml", "front.csv", "front.units.json",
           "trials.parquet", "front.png")
STUDY = "study.db"


def run(args) -> int:
    from ..errors import PollardError
    from ..io.atomic import check_outputs
    from ..synthesis.api import design
    from ..synthesis.front import EXACT, FrontResolution
    from ..synthesis.storage import check_study_file, require_optuna
    from ..synthesis.study import DesignOptions, finished

    out = Path(args.out)
    require_optuna()  # the extra, before anything else: a missing one is the only line
    files = [out / f for f in OUTPUTS]
    check_outputs(*files, folders=(out,))
    refuse_inputs(args, *files, out / STUDY, also=[("the job", args.job),
                                                    ("the design space", args.space)])
    check_study_file(out / STUDY, args.resume)  # another job or space: checked when opened
    if args.dask:
        from ..sweep.backends import require_distributed

        require_distributed()
    made = [p for p in (out, out / STUDY) if not os.path.lexists(p)]  # this run's to make
    before = _signature(out / STUDY)
    options = DesignOptions(trials=args.trials, workers=args.workers, dask=args.dask,
                            seed=args.seed, population=args.population, study=out / STUDY,
                            resume=args.resume, pick=args.pick, progress=not args.quiet,
                            front=EXACT if args.exact_front else FrontResolution())
    try:
        with warnings_as_notes(args):
            result = design(args.job, args.space, options)
        result.write(out)  # a full disk here: the study is kept, and said so
    except KeyboardInterrupt as exc:
        if not (out / STUDY).is_file():
            raise  # stopped before the study began: nothing was written
        held = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT, signal.SIGTERM})
        try:  # a second signal waits until this is said
            kept = _kept(_finished_count(out / STUDY, finished))
            how, code = (("interrupted", 130) if type(exc) is KeyboardInterrupt else
                         ("terminated", 143))
            print(f"pollard-pin design: {how}: {kept} finished evaluations kept in "
                  f"{out / STUDY} (--resume continues the study)", file=sys.stderr)
        finally:
            signal.pthread_sigmask(signal.SIG_SETMASK, held)
        return code
    except PollardError as exc:
        _after_failure(out, made, before, exc)
        raise
    print("\n".join(result.summary_lines()))
    wrote(out, f" (chosen: design {result.design['design']}; the study: {out / STUDY})")
    return 0


def _kept(count: int | None) -> str:
    """How many finished evaluations a study holds, in words: ``count``, or "all" when
    :func:`_finished_count` cannot say."""
    return "all" if count is None else str(count)


def _finished_count(path: Path, finished) -> int | None:
    """How many finished evaluations the study file holds (None: it cannot say)."""
    from ..synthesis.storage import STUDY_NAME, require_optuna

    optuna = require_optuna()
    try:
        storage = optuna.storages.RDBStorage(f"sqlite:///{path.resolve()}")
        try:
            return finished(optuna.load_study(study_name=STUDY_NAME, storage=storage))[0]
        finally:
            storage.engine.dispose()
    except Exception:  # noqa: BLE001 — a count for the message, never a second failure
        return None


def _signature(path: Path) -> tuple | None:
    """(size, modification time) of a file, None if there is none: whether a run wrote it."""
    try:
        st = os.stat(path)
    except OSError:
        return None
    return st.st_size, st.st_mtime_ns


def _after_failure(out: Path, made: list[Path], before: tuple | None,
                   exc: BaseException) -> None:
    """After a refusal or failure: a study file this run started that holds no finished
    evaluation (a full disk while it was made, a scheduler that never answered) is removed
    with its logs, and the folder if this run made it and it is empty, so that "nothing
    written" holds; a study this run wrote that holds evaluations is kept, and the error
    says so (``exc.kept``, which the command line says instead of "nothing written"). A
    study refused before it was opened is as it was."""
    from ..synthesis.study import finished

    study = out / STUDY
    if not study.is_file() or (study not in made and _signature(study) == before):
        return
    count = _finished_count(study, finished)
    if study in made and not count:
        for path in (study, *(Path(f"{study}{end}") for end in ("-wal", "-shm", "-journal"))):
            with contextlib.suppress(FileNotFoundError):
                path.unlink()
        if out in made:
            with contextlib.suppress(OSError):  # not empty: left alone
                out.rmdir()
        return
    exc.kept = (f"{_kept(count)} finished evaluations kept in {study}: "
                "--resume continues the study")


def add_parser(sub, parents) -> None:
    p = command(sub, parents, "design", "design the robot for a paint job: lengths, joint "
                "ranges, motors and the number of robots (NSGA-II; docs/model.md §31)", run)
    p.add_argument("--job", type=name, required=True, metavar="JOB.toml",
                   help="the paint job (any kind: panel, part, line, cell)")
    p.add_argument("--space", type=name, required=True, metavar="SPACE.toml",
                   help="the design space: [bounds], [[scale]], catalogue, robots (see "
                        "examples/design/)")
    p.add_argument("--out", type=name, required=True, metavar="DIR",
                   help="output folder: params.toml, actuators.toml (robots.toml for a cell) "
                        "of the chosen design, front.csv, trials.parquet, front.png and the "
                        "study database study.db")
    p.add_argument("--trials", type=count(1, 10**6), default=200, metavar="N",
                   help="evaluations the study holds when it stops (a resumed study counts "
                        "those it had)")
    p.add_argument("--resume", action="store_true",
                   help="continue the study in DIR/study.db (started with the same job and "
                        "space)")
    p.add_argument("--dask", type=scheduler_address, metavar="ADDRESS", default=None,
                   help="evaluate on this Dask scheduler (needs the cluster extra; "
                        "default: local processes)")
    p.add_argument("--workers", type=count(1, 1024), default=None, metavar="N",
                   help="local processes (1 = this process; default: all cores)")
    p.add_argument("--pick", type=count(1), default=None, metavar="N",
                   help="choose front row N (front.csv's design N); default: the rule, "
                        "within motor use 0.9 the fewest robots, then the most parts per "
                        "hour, then the least moving mass")
    p.add_argument("--exact-front", action="store_true",
                   help="report the exact Pareto front (default: of designs closer than "
                        "parts/h 1 %%, motor use 0.01, kmin 10 %%, moving mass 2 %%, one, "
                        "docs/model.md §31.5)")
    p.add_argument("--seed", type=count(0, SEEDS - 1), default=0, metavar="S",
                   help="the sampler's seed, 0 to 2^32 − 1 (numpy's range; default: 0)")
    p.add_argument("--population", type=count(2, 10**4), default=24, metavar="N",
                   help="NSGA-II's population (designs per generation)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
