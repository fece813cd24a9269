"""pollard_pin.synthesis (synthesis/api.py): the front of every evaluation, re-planned, the baseline
and the chosen design, against the stand-in's closed-form figures."""
import itertools

import pytest
import synthesis_stub as stub
from synthesis_runs import run_stub, stub_result  # noqa: F401 — the shared study

from pollard_pin.errors import SolveError
from pollard_pin.synthesis.front import (
    SENSES,
    FrontResolution,
    dominates,
    non_dominated,
    rank_key,
)


def test_the_front_is_non_dominated_over_every_evaluation(stub_result):  # noqa: F811
    feasible = [r for r in stub_result.trials if r["feasible"]]
    assert feasible and stub_result.front
    for d in stub_result.front:  # brute force: no evaluation beats a front design
        assert not any(dominates({n: r[n] for n in SENSES}, d["objectives"]) for r in feasible)
    for a, b in itertools.permutations(stub_result.front, 2):
        assert not dominates(a["objectives"], b["objectives"])
    # every feasible evaluation is ε-dominated by a front design (the default resolution: a
    # front design at most one box worse in each objective, Laumanns et al.'s (1+ε) rule)
    res = FrontResolution()
    front = [d["objectives"] for d in stub_result.front]
    for r in feasible:
        assert any(all(_within(f[n], r[n], SENSES[n], getattr(res, n, 0.0),
                               n in res.RELATIVE) for n in SENSES) for f in front), r
    assert len(front) < len(non_dominated([{n: r[n] for n in SENSES} for r in feasible]))


def _within(f, r, sense, eps, relative):
    """Whether ``f`` is no worse than ``r`` by more than ε (relative: a factor 1 + ε)."""
    if relative:
        return (f * (1 + eps) >= r) if sense > 0 else (f <= r * (1 + eps))
    return sense * f >= sense * r - eps


def test_front_designs_are_replanned_in_full_and_ranked(stub_result):  # noqa: F811
    keys = [rank_key(d["objectives"]) for d in stub_result.front]
    assert keys == sorted(keys)
    assert [d["design"] for d in stub_result.front] == list(range(1, len(keys) + 1))
    for d in stub_result.front:
        objectives, constraints = stub.figures(d["values"], {"shift": 0.0})
        assert d["level"] == "full"
        assert d["objectives"] == pytest.approx(objectives)
        assert all(v <= 0 for v in constraints.values())
    assert stub_result.chosen == 0  # the rule's design is the first row


def test_the_thesis_robot_is_the_baseline(stub_result):  # noqa: F811
    b = stub_result.baseline
    assert b["values"] == stub.StubSpace().baseline()
    objectives, _ = stub.figures(b["values"], {"shift": 0.0})
    assert b["feasible"] and b["objectives"] == pytest.approx(objectives)
    lines = stub_result.summary_lines()
    assert lines[0].startswith("40 evaluations, ")
    assert lines[1].startswith("thesis robot: 200 parts/h, 2 robots")
    assert len(lines) == 2 + len(stub_result.front)
    assert lines[2].startswith("design 1 (chosen): ") and "(-1)" in lines[2]  # one robot fewer


def test_pick_chooses_a_front_row(tmp_path):
    result = run_stub(None, 12, pick=2)
    assert result.chosen == 1 and result.design["design"] == 2


def test_a_space_with_no_feasible_design_names_the_binding_constraint():
    impossible = type("Impossible", (), {
        "OBJECTIVES": stub.OBJECTIVES, "prepare": stub.prepare,
        "baseline_values": staticmethod(stub.baseline_values),
        "evaluate": staticmethod(lambda values, ctx, level="screen": stub.Evaluation(
            level, False, {}, {"reach": 1.0, "motors": -1.0}, "reach"))})
    from pollard_pin.synthesis.api import design
    from pollard_pin.synthesis.study import DesignOptions

    with pytest.raises(SolveError, match=r"no design of the space paints the job in 5 "
                                         r"evaluations; the binding constraint most often: "
                                         r"reach \(5 of 5\)"):
        design(stub.StubJob(), stub.StubSpace(), DesignOptions(trials=5, workers=1),
               evaluator=impossible)


def test_a_searched_front_is_planned_again_exactly():
    """A study at the search's fidelity (the stand-in's: the film unchecked) plans its front
    exactly before reporting it: a front design the exact film check refuses (y above
    SEARCH_FILM) leaves it, with a note, and the designs it hid take its place; the front is
    the ε-front of the exactly feasible designs, by brute force."""
    from pollard_pin.synthesis.evaluation import SearchFidelity

    calls = []

    def counted(values, ctx, level="screen"):
        calls.append(level)
        return stub.evaluate(values, ctx, level)

    ev = type("Counted", (), {"OBJECTIVES": stub.OBJECTIVES, "prepare": stub.prepare,
                              "baseline_values": staticmethod(stub.baseline_values),
                              "evaluate": staticmethod(counted)})
    result = run_stub(None, 40, search=SearchFidelity(), evaluator=ev)
    searched = [r for r in result.trials if r["feasible"]]
    assert searched and {r["level"] for r in result.trials} == {"screen", "search"}
    # each trial planned once: the front's, those that left it, and the baseline (with the
    # front's plans, not again when it was among them)
    planned = {d["trial"] for d in result.front} | {int(n.split()[1]) for n in result.notes}
    base_again = result.baseline["trial"] not in planned
    assert calls.count("full") == len(result.notes) + len(result.front) + base_again
    assert any(r["y"] > stub.SEARCH_FILM for r in searched)  # the search let them through
    assert result.notes and all("left the front when planned in full: film" in n
                                for n in result.notes)
    for d in result.front:
        objectives, _ = stub.figures(d["values"], {"shift": 0.0})
        assert d["level"] == "full" and "fidelity" not in d["figures"]
        assert d["values"]["y"] <= stub.SEARCH_FILM and d["objectives"] == pytest.approx(
            objectives)
    exact = [{n: r[n] for n in SENSES} for r in searched if r["y"] <= stub.SEARCH_FILM]
    front = [d["objectives"] for d in result.front]
    res = FrontResolution()  # every exactly feasible design ε-dominated by a front design
    for o in exact:
        assert any(all(_within(f[n], o[n], SENSES[n], getattr(res, n, 0.0),
                               n in res.RELATIVE) for n in SENSES) for f in front), o
    assert result.baseline["feasible"] and result.baseline["objectives"] == pytest.approx(
        stub.figures(result.baseline["values"], {"shift": 0.0})[0])


def test_a_screened_front_is_planned_in_full():
    """DesignOptions(screen_only=True): every design judged by the screen alone, the front
    and the baseline planned in full at the end."""
    result = run_stub(None, 16, screen_only=True)
    assert {r["level"] for r in result.trials} == {"screen"}
    assert result.front and all(d["level"] == "full" for d in result.front)
    for d in result.front:
        assert d["objectives"] == pytest.approx(stub.figures(d["values"], {"shift": 0.0})[0])
    assert result.baseline["feasible"]


def test_an_unreachable_scheduler_is_refused_before_any_work_or_write(tmp_path):
    """A well-formed scheduler address that does not answer: one line before the job is
    prepared, the screened ladder run (84 s of the example's) or the study file made."""
    import dask

    calls = []

    def prepare(*args, **kwargs):
        calls.append("prepare")
        return stub.prepare(*args, **kwargs)

    spy = type("Spy", (), {"OBJECTIVES": stub.OBJECTIVES, "prepare": staticmethod(prepare),
                           "baseline_values": staticmethod(stub.baseline_values),
                           "evaluate": staticmethod(stub.evaluate)})
    with dask.config.set({"distributed.comm.timeouts.connect": "0.5s"}), \
            pytest.raises(SolveError, match=r"^cannot connect to the Dask scheduler at "
                                            r"'tcp://127.0.0.1:1': "):
        run_stub(tmp_path / "study.db", 8, dask="tcp://127.0.0.1:1", evaluator=spy)
    assert calls == [] and list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("args, says", [
    ((3, stub.StubSpace()), "job = 3: expected a paint job (PaintJob, PartJob) or a job file's "
                            "path, got int"),
    ((None, stub.StubSpace()), "job = None: expected a paint job"),
    ((stub.StubJob(), 3), "space = 3: expected a DesignSpace, a space file's path or its table "
                          "(a Mapping), got int"),
    ((stub.StubJob(), [0.3, 0.4]), "space = [0.3, 0.4]: expected a DesignSpace"),
    ((stub.StubJob(), stub.StubSpace(), 3), "options = 3: expected DesignOptions or None, "
                                            "got int"),
], ids=["job", "job None", "space", "space list", "options"])
def test_a_wrong_type_is_one_line_naming_the_argument(args, says):
    # the old code gave AttributeError: 'int' object has no attribute 'line' (or 'robots')
    from pollard_pin.errors import InputError
    from pollard_pin.synthesis.api import design

    calls = []
    spy = type("Spy", (), {"OBJECTIVES": stub.OBJECTIVES,
                           "prepare": staticmethod(lambda *a, **k: calls.append(a)),
                           "baseline_values": staticmethod(stub.baseline_values),
                           "evaluate": staticmethod(stub.evaluate)})
    with pytest.raises(InputError) as e:
        design(*args, evaluator=spy)
    assert str(e.value) == says or str(e.value).startswith(says), str(e.value)
    assert "\n" not in str(e.value) and len(str(e.value)) <= 250 and calls == []


def test_a_progress_that_is_no_function_is_refused_first():
    from pollard_pin.errors import InputError
    from pollard_pin.synthesis.api import design
    from pollard_pin.synthesis.study import DesignOptions

    with pytest.raises(InputError, match=r"^progress = 3: expected a function or None, got int$"):
        design(stub.StubJob(), stub.StubSpace(), DesignOptions(trials=2, workers=1), evaluator=stub,
               progress=3)


def test_a_front_design_is_planned_again_with_its_own_search_notes():
    """What the search noted of a design (Evaluation.notes: its layout and line plans'
    searches) is stored with its trial and handed back with that design, and no other, when
    the front (or the baseline) is planned exactly."""
    from dataclasses import dataclass, fields

    from pollard_pin.synthesis.evaluation import SearchFidelity

    @dataclass(frozen=True)
    class Noted(stub.Evaluation):
        notes: dict | None = None

    got = []

    def noting(values, ctx, level="screen", notes=None):
        ev = stub.evaluate(values, ctx, level)
        if level == "full":
            got.append((dict(values), notes))
            return ev
        own = {"for": [values["chain0.x32"], values["y"], values["robots"]]}
        return Noted(**{f.name: getattr(ev, f.name) for f in fields(ev)}, notes=own)

    ev = type("Noting", (), {"OBJECTIVES": stub.OBJECTIVES, "prepare": stub.prepare,
                             "baseline_values": staticmethod(stub.baseline_values),
                             "evaluate": staticmethod(noting)})
    result = run_stub(None, 16, search=SearchFidelity(), evaluator=ev)
    assert got and len(got) >= len(result.front)
    for values, notes in got:  # every one a searched design's, with its own notes
        assert notes == {"for": [values["chain0.x32"], values["y"], values["robots"]]}


def test_an_exact_resolution_reports_the_exact_front():
    """DesignOptions(front=EXACT), every resolution 0: the front is the plain Pareto front of
    every feasible evaluation (each on it, or its figures beaten or equalled by one on it)."""
    from pollard_pin.synthesis.front import EXACT

    result = run_stub(None, 24, front=EXACT)
    front = [d["objectives"] for d in result.front]
    feasible = [{n: r[n] for n in SENSES} for r in result.trials if r["feasible"]]
    assert len(front) == len(non_dominated(feasible))
    for o in feasible:
        assert o in front or any(dominates(f, o) for f in front)
    assert result.summary_lines()[0].count("box") == 0
