"""What a design study gives back (:class:`DesignResult`): every evaluation, the Pareto front
(each design judged by its full plan), the thesis robot as the baseline, the chosen design and
its files, and :meth:`DesignResult.write`, which writes what ``pollard-pin design`` writes."""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

from ..checks import file_path
from .evaluation import UNITS
from .front import EXACT, SENSES, FrontResolution, gains

# The files of the chosen design (robots.toml for a cell only), then the study's tables
DESIGN_FILES = ("params.toml", "actuators.toml", "robots.toml")
TABLES = ("front.csv", "front.units.json", "trials.parquet", "front.png")


def shown(variables, values: Mapping) -> dict:
    """A design's values as its tables show them: a categorical's choice (a motor's name, a
    gear ratio), not its index."""
    out = {}
    for v in variables:
        value = values.get(v.name)
        out[v.name] = (v.choices[int(value)] if v.kind == "categorical" and value is not None
                       else value)
    return out


def variable_unit(v) -> str:
    """A design variable's unit in the tables: its own (``unit``) if it has one, else by its
    kind and name (a bound's: models/pollard.toml's, m or deg)."""
    if getattr(v, "unit", None):
        return v.unit
    if v.kind == "categorical":
        return "choice"
    return {"scale.": "1 (factor)", "place.": "m", "robots": "1"}.get(
        next((p for p in ("scale.", "place.") if v.name.startswith(p)), v.name),
        "as models/pollard.toml (m, deg)")


@dataclass(frozen=True)
class DesignResult:
    """A finished design study.

    Attributes
    ----------
    variables : tuple
        The design variables (``name``, ``low``, ``high``, ``kind``, ``choices``).
    objectives : tuple of str
        The objectives' names, in the study's order.
    trials : tuple of dict
        One row per evaluation: ``trial``, ``state``, ``level``, ``feasible``, ``binding``,
        each variable, each objective (None where the design has no figure), each constraint
        as ``c_<name>`` and the evaluation's wall time ``seconds``; a categorical variable's
        choice (not its index).
    front : tuple of dict
        The front's designs (its ε-front at ``resolution``), each judged by its full plan, in
        the order of
        :func:`~pollard_pin.synthesis.front.rank_key`: ``design`` (1, 2, …), ``trial``,
        ``values``, ``objectives``, ``figures``, ``files`` (name → TOML text).
    baseline : dict
        The thesis robot (every variable at today's value or nearest choice): ``values``,
        ``feasible``, ``objectives`` (None when it cannot paint the job), ``binding``.
    chosen : int
        The chosen design's index in ``front``.
    study : str or None
        The study file.
    seconds : float
        The wall time of this run [s].
    notes : tuple of str
        What the reader should know (designs dropped when planned in full …).
    resolution : FrontResolution
        The resolution the front told designs apart at (front.csv's metadata says it).
    """

    variables: tuple
    objectives: tuple
    trials: tuple
    front: tuple
    baseline: dict
    chosen: int
    study: str | None = None
    seconds: float = 0.0
    notes: tuple = field(default=())
    resolution: FrontResolution = EXACT

    @property
    def design(self) -> dict:
        """The chosen front design."""
        return self.front[self.chosen]

    @property
    def feasible(self) -> int:
        """How many evaluations were feasible."""
        return sum(bool(r.get("feasible")) for r in self.trials)

    def gains(self) -> list[str]:
        """One line per front design: its figures and what it gains against the baseline."""
        base = self.baseline["objectives"] if self.baseline.get("feasible") else None
        mark = {self.chosen: " (chosen)"}
        return [f"design {d['design']}{mark.get(k, '')}: {gains(d['objectives'], base)}"
                for k, d in enumerate(self.front)]

    def summary_lines(self) -> list[str]:
        """What ``pollard-pin design`` prints: the study's counts, the baseline, one line per
        front design."""
        b = self.baseline
        base = (gains(b["objectives"], None) if b.get("feasible") else
                f"cannot paint the job (binding: {b.get('binding') or 'unknown'})")
        return [f"{len(self.trials)} evaluations, {self.feasible} feasible, front of "
                f"{len(self.front)} designs{self.resolution.phrase()} ({self.seconds:.1f} s)",
                f"thesis robot: {base}", *self.gains(), *self.notes]

    def front_rows(self) -> list[dict]:
        """front.csv's rows: the baseline (``design`` 0), then each front design."""
        rows = []
        for d in (self.baseline_row(), *self.front):
            obj = d.get("objectives") or {}
            rows.append({"design": d["design"], "trial": d.get("trial"),
                         "feasible": bool(d.get("feasible", True)),
                         **{n: obj.get(n) for n in self.objectives},
                         **shown(self.variables, d["values"])})
        return rows

    def baseline_row(self) -> dict:
        """The thesis robot as front.csv's row 0."""
        return {"design": 0, "trial": None, **self.baseline}

    def units(self) -> dict:
        """Each table column's unit."""
        units = {"design": "1 (0: the thesis robot)", "trial": "1", "feasible": "1",
                 "state": "", "level": "", "binding": "", "error": "", "seconds": "s",
                 **{v.name: variable_unit(v) for v in self.variables},
                 **{n: UNITS.get(n) or "1" for n in self.objectives}}
        for row in self.trials:
            units.update({c: "1 (≤ 0: met)" for c in row if c.startswith("c_")})
        return units

    def write(self, folder: str | Path) -> Path:
        """Write the chosen design's params.toml, actuators.toml (robots.toml for a cell),
        front.csv (+ front.units.json), trials.parquet and front.png in ``folder``, every
        one or none; the folder.

        Parameters
        ----------
        folder : str or Path
            The output folder (created if missing).

        Returns
        -------
        Path
            The folder.
        """
        from ..io.atomic import all_or_nothing, atomic_open, make_folder
        from ..viz.design import write_front_png
        from .table import write_rows

        folder = make_folder(file_path(folder, "folder"))
        meta = {"objectives": {n: "max" if SENSES[n] > 0 else "min" for n in self.objectives},
                "chosen": self.design["design"], "study": self.study,
                "front_resolution": self.resolution.described()}
        with all_or_nothing():
            for name, text in self.design["files"].items():
                with atomic_open(folder / name) as f:
                    f.write(text)
            write_rows(folder / "front.csv", self.front_rows(), self.units(), meta,
                       first=("design", "trial", "feasible", *self.objectives))
            write_rows(folder / "trials.parquet", list(self.trials), self.units(), meta,
                       first=("trial", "state", "level", "feasible", "binding",
                              *self.objectives))
            feasible = [r for r in self.trials if r.get("feasible")]
            write_front_png(folder / "front.png", [d["objectives"] for d in self.front],
                            [{n: r[n] for n in self.objectives} for r in feasible],
                            self.baseline["objectives"] if self.baseline.get("feasible")
                            else None, self.chosen)
        return folder

