"""Notes of a line plan's searches (docs/model.md §31.5): what :func:`.line.world.plan_world`
searched before it sampled and checked the path — the turnarounds' durations, the delay, the
return — kept by a fingerprint of everything that search reads, so that the same plan made
again at another fidelity of its checks (``check_refine``, the clearance's stride, the film's
grid: none read there) takes them instead of searching again, and runs only its own final
motor check on the path. Outside :func:`plan_notes` nothing is kept.

A note is plain data (numbers, lists, strings): a design study stores a searched design's
notes with its trial and hands them back with the design when it is planned exactly. A
search that refused the line speed (a :class:`LineSpeedError`, as a slow line's first try
does before it waits at the turnarounds) is noted as that refusal, raised again in its words.
"""
from __future__ import annotations

import hashlib
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import replace

import numpy as np

from ..errors import LineSpeedError

_NOTES: ContextVar[dict | None] = ContextVar("line_plan_notes", default=None)
SHAPE_SAMPLES = 97  # program times (besides its pieces' ends and middles) in the fingerprint


@contextmanager
def plan_notes(notes: dict | None = None) -> Iterator[dict]:
    """Within: every line plan's searches noted in ``notes`` (a new dict if None), and a
    plan whose fingerprint is noted there takes the note instead of searching (the
    dict yielded; it gains the notes made)."""
    notes = {} if notes is None else notes
    token = _NOTES.set(notes)
    try:
        yield notes
    finally:
        _NOTES.reset(token)


def fingerprint(robot, act, program, rel, speed: float, e, policy, screen: bool) -> str:
    """A digest of what :func:`.line.world.plan_world`'s searches read: the model (its
    parameters and gravity), the motors, the relative program (``rel``, at its guess: its
    pieces and its motion at their ends and middles and at SHAPE_SAMPLES times), the guess,
    the time step, the line's speed and direction and the policy but for its checks'
    fidelity (``check_refine``, ``clearance_stride``, ``name_speeds``)."""
    h = hashlib.blake2b(digest_size=16)
    t = np.unique(np.concatenate([rel.coarse_times(),
                                  np.linspace(0.0, rel.total, SHAPE_SAMPLES)]))
    for x in (rel.start, rel.duration, t, *rel.evaluate(t), program.guess, e,
              robot.model.gravity.linear):
        h.update(np.ascontiguousarray(x, dtype=float).tobytes())
    plain = replace(policy, check_refine=1, clearance_stride=1, name_speeds=False)
    h.update(repr((rel.kind, rel.passes_only, float(speed), float(program.dt), program.where,
                   program.passes, program.source, bool(screen), robot.params, act.units,
                   plain)).encode())
    return h.hexdigest()


def noted(search: Callable[[], dict], robot, act, program, rel, speed: float, e, policy,
          screen: bool) -> dict:
    """``search()`` (a dict of plain numbers), or within :func:`plan_notes` its note by the
    inputs' :func:`fingerprint`: taken if there (a noted refusal raised again), else made and
    noted."""
    notes = _NOTES.get()
    if notes is None:
        return search()
    key = fingerprint(robot, act, program, rel, speed, e, policy, screen)
    note = notes.get(key)
    if note is not None:
        if "refused" in note:
            raise LineSpeedError(*note["refused"])
        return note
    try:
        note = search()
    except LineSpeedError as exc:
        if type(exc) is LineSpeedError:  # its words, side, reason and hint: all it holds
            notes[key] = {"refused": [str(exc), bool(exc.too_fast), str(exc.why),
                                      None if exc.hint is None else float(exc.hint)]}
        raise
    notes[key] = note
    return note


__all__ = ["SHAPE_SAMPLES", "fingerprint", "noted", "plan_notes"]
