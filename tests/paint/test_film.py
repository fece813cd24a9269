"""The film map's budgets (docs/model.md §21): checked before its grid or its integration."""
from dataclasses import replace
from pathlib import Path

import pytest

from pollard_pin.dynamics.motors import load_actuators
from pollard_pin.paint import film as film_module
from pollard_pin.paint.errors import PlanError
from pollard_pin.paint.film import film_resolution, plan_film
from pollard_pin.paint.job import load_job
from pollard_pin.paint.plan import plan_paint

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def test_film_grid_budget_is_checked_in_floats():
    job = load_job(EXAMPLES / "paint.toml")
    assert film_resolution(job) == pytest.approx(job.sigma / 3)
    for res, says in ((1e-6, r"makes 3.12e\+10 film points"), (1e-300, "makes inf film points")):
        with pytest.raises(PlanError, match=says):
            film_resolution(job, res)  # was a 600-digit count in the CLI, no check in here


def test_film_pairs_budget(robot, monkeypatch):
    job = load_job(EXAMPLES / "paint.toml")
    job = replace(job, width=0.1, height=0.05)
    plan = plan_paint(robot, job, load_actuators(EXAMPLES / "actuators.toml"))
    monkeypatch.setattr(film_module, "MAX_FILM_PAIRS", 1e5)
    with pytest.raises(PlanError, match="point × sample pairs"):
        plan_film(plan)
