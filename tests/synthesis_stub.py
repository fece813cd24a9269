"""A stand-in design evaluator for the study's tests (tests/synthesis/): the interface of
pollard_pin.synthesis.evaluation (``prepare``, ``evaluate``, ``OBJECTIVES``) and of a design space
(``variables``, ``fingerprint``, ``baseline``), over closed-form figures, so that a study of
dozens of designs takes a fraction of a second. Its params.toml moves chain0.x32 within a
range the model accepts, so the written files read back through the model's own loader. As
the real evaluator, its ``level="full"`` screens first and gives the screen's evaluation for a
design it rejects, and a categorical variable's value is an index into its choices. With a
context prepared with a search fidelity, its ``level="full"`` also checks the film (y at most
SEARCH_FILM) and its ``level="search"`` is the full level without it (the coarser check
passes every design): the study's front must be planned again exactly.

``STUB_DELAY`` (seconds, an environment variable) makes every evaluation that slow: a study
then stays busy long enough to be stopped.
"""
from __future__ import annotations

import hashlib
import json
import os
import time
from dataclasses import dataclass, field
from pathlib import Path

OBJECTIVES = ("parts_per_hour", "robots", "motor_use", "kmin", "moving_mass")
ROOT = Path(__file__).resolve().parent.parent
ACTUATORS = (ROOT / "examples" / "actuators.toml").read_text(encoding="utf-8")
MOTORS = {"small": 0.4, "medium": 0.7, "large": 1.1}  # kg
SEARCH_FILM = 0.9  # y above it fails the exact film check the search's coarser one passes


@dataclass(frozen=True)
class Variable:
    name: str
    low: float
    high: float
    kind: str
    choices: tuple = ()
    unit: str = ""


@dataclass(frozen=True)
class Evaluation:
    level: str
    feasible: bool
    objectives: dict
    constraints: dict
    binding: str | None
    figures: dict = field(default_factory=dict)
    params_toml: str | None = None
    actuators_toml: str | None = None
    robots_toml: str | None = None


@dataclass(frozen=True)
class StubSpace:
    """x, y in [0, 1], a motor of three, 1..3 robots; ``shift`` makes another space."""

    shift: float = 0.0

    def variables(self):
        return [Variable("chain0.x32", 0.30, 0.36, "float", unit="m"),
                Variable("y", 0.0, 1.0, "float", unit="1"),
                Variable("motor", 0, len(MOTORS) - 1, "categorical", tuple(MOTORS)),
                Variable("robots", 1, 3, "int", unit="1")]

    def fingerprint(self) -> str:
        return hashlib.sha256(json.dumps(["stub", self.shift]).encode()).hexdigest()[:16]

    def baseline(self):
        return {"chain0.x32": 0.33, "y": 0.5, "motor": 1, "robots": 2}  # motor: an index


@dataclass(frozen=True)
class StubJob:
    speed: float = 0.012

    def to_dict(self):
        return {"line": {"speed": self.speed}}


def baseline_values(space, ctx=None):
    return space.baseline()


def prepare(job, space, search=None):
    return {"speed": job.speed, "shift": space.shift, "search": search}


def figures(values: dict, ctx: dict) -> tuple[dict, dict]:
    """(objectives, screen constraints) of a design, closed form."""
    x = (values["chain0.x32"] - 0.30) / 0.06  # 0..1
    y, n = values["y"], values["robots"]
    m = list(MOTORS.values())[values["motor"]]  # the evaluator takes a choice's index
    objectives = {"parts_per_hour": 100.0 * n * (0.5 + x) * (1.0 + ctx["shift"]),
                  "robots": float(n), "motor_use": 0.3 + 0.6 * x * (1.2 - m) + 0.2 * y,
                  "kmin": 1e5 * (1.0 - 0.5 * x) * (0.5 + y), "moving_mass": 2.0 + 3 * x + 6 * m
                  + y}
    constraints = {"reach": 0.4 - x - y}  # reach needs x + y >= 0.4
    return objectives, constraints


def evaluate(values, ctx, level="screen"):
    delay = float(os.environ.get("STUB_DELAY", "0") or 0)
    if delay:
        time.sleep(delay)
    objectives, constraints = figures(values, ctx)
    if level == "search" and ctx.get("search") is None:  # no search fidelity: planned exactly
        level = "full"
    if level in ("search", "full") and constraints["reach"] > 0:  # they screen first
        level = "screen"
    if level in ("search", "full"):
        constraints["motors"] = objectives["motor_use"] - 1.0  # the full plan's motor check
    if level == "full" and ctx.get("search") is not None:  # the film, judged exactly: a
        constraints["film"] = values["y"] - SEARCH_FILM  # y above SEARCH_FILM fails it
    binding = max(constraints, key=constraints.get)
    feasible = all(v <= 0 for v in constraints.values())
    params = f"[chain0]\nx32 = {values['chain0.x32']!r}\n"
    robots = ("".join(f"[[robot]]\nname = \"r{i}\"\nbase = [0.0, {0.4 * i}, 0.0]\n"
                      for i in range(values["robots"])) if values["robots"] > 1 else None)
    seen = {"cycle_time": 10.0 / (0.5 + values["y"])}
    if level == "search":
        seen["fidelity"] = "search"
    return Evaluation(level, feasible, objectives if feasible or level == "screen" else {},
                      constraints, binding if not feasible else None, seen, params, ACTUATORS,
                      robots)
