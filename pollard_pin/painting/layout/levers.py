"""What ``--robots auto`` tries once the plain proposal is refused: a cell's levers set by rule
from the job (docs/model.md §26.5, "The levers found by auto").

A part whose strokes bend towards an edge (a bevel, a rounded edge) is refused by the plain
proposal for reasons the levers answer (its ramps at a seam or an edge out of the band, the
motors following the turning normal, the top robot at its wrist's singularity). Each lever
left at its default is set from the job:

- ``seam_run`` = STEP, one step of the bands' grid (the least run the split resolves): the
  trigger closes at the seam on the constant-speed stroke, so the film is the split's
  (§26.3), and a ramp at a seam keeps R − STEP of the band's room;
- ``smoothing`` = 2·run-on (EXTENSION σ each side: the spot's width at a part's free edge),
  every robot's passes the same;
- ``edge_room`` = v·τ₀/2 up to the millimetre, the run of a ramp past its pass at the first
  guess of its duration (τ₀ = 4v/``first_deceleration``, v the pass speed; the search may
  find it longer);
- ``end_pitch`` = END_PITCH, the top robot turned about the line off the wrist's
  singularity.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

from ..cell.bands import STEP, Strokes
from ..errors import PlanError
from ..job import PartJob
from ..passes.surface import pass_spacing, pass_speed

END_PITCH = -5.0  # deg about the line: the top robot off its wrist's singularity (§26.5)


@dataclass(frozen=True)
class Levers:
    """The levers a search used beyond the plain proposal (None: left as given)."""

    seam_run: float | None = None
    smoothing: float | None = None
    edge_room: float | None = None
    end_pitch: float | None = None

    def flags(self) -> str:
        """The command line's flags that set them ('--seam-run 0.005 --smoothing 0.06')."""
        return " ".join(f"--{k.replace('_', '-')} {v:.4g}" for k, v in self.as_dict().items())

    def as_dict(self) -> dict:
        """The levers set, by name (paint.json's ``levers``)."""
        return {k: v for k, v in vars(self).items() if v is not None}


def levers_for(job, strokes: Strokes, policy, layout) -> Levers | None:
    """The levers left at their defaults in ``policy`` (PlannerPolicy) and ``layout``
    (LayoutOptions), each set by its rule (module docstring), for a part (None: a panel, whose
    flat strokes the levers do not answer, a pass speed refused, or nothing left to set)."""
    if not isinstance(job, PartJob):
        return None
    try:
        v = pass_speed(job, pass_spacing(job))
    except PlanError:  # no pass at all (a unit slip): the plain refusal says why
        return None
    ramp = v * policy.first_guess(v) / 2
    found = Levers(
        seam_run=STEP if policy.seam_run is None else None,
        smoothing=2 * strokes.run_on if not policy.smoothing else None,
        edge_room=math.ceil(ramp * 1e3 - 1e-9) / 1e3 if not layout.edge_room else None,
        end_pitch=END_PITCH if not layout.end_pitch else None)
    return found if found.as_dict() else None


def with_levers(options, layout, levers: Levers):
    """(PaintOptions, LayoutOptions) with ``levers`` set."""
    policy = options.policy
    policy = replace(policy, **{k: v for k, v in levers.as_dict().items()
                                if k in ("seam_run", "smoothing")})
    layout = replace(layout, **{k: v for k, v in levers.as_dict().items()
                                if k in ("edge_room", "end_pitch")})
    return replace(options, policy=policy), layout


__all__ = ["END_PITCH", "Levers", "levers_for", "with_levers"]
