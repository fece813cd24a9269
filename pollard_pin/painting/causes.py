"""What a planner's refusal says binds, and its figure in a few words (docs/model.md §26.5):
one rule for the layout search's refusal (:func:`search_refusal`, of
:func:`pollard_pin.painting.layout.auto.fewest_robots`)
and the design study's infeasible designs (:mod:`pollard_pin.synthesis.evaluation`).

:func:`binding_of` sorts a refusal by the constraint its words name, in the design study's
vocabulary (``clearance``, ``motors``, ``reach``, ``film``, else ``plan``). :func:`cause_of`
narrows it where the words say more (``band``: the robots' bands cannot hold the part's zones
with their run-outs; ``line speed``: another line speed paints the part) and reads the figure
the refusal gives ("motor 126 %", "bottom band 40 mm short of the run-on", "turnarounds out
of reach"). A refusal whose words it does not know keeps its first clause.
"""
from __future__ import annotations

import re
from dataclasses import dataclass

from ..errors import say_less, without_asides

#: The constraints :func:`cause_of` names: :func:`binding_of`'s and the two it narrows to.
BINDINGS = ("reach", "band", "motors", "clearance", "film", "line speed", "plan")
# a refusal's words → the design study's constraint, first match
_WORDS = (("clearance", "clearance"), ("closer than", "clearance"), ("apart", "clearance"),
          ("torque", "motors"), ("motor", "motors"), ("rating", "motors"), ("reach", "reach"),
          ("limit", "reach"), ("singular", "reach"), ("film", "film"))
_ROBOT = re.compile(r"^robot '([^']+)': ")
_NUMBER = r"(-?\d+(?:\.\d+)?)"
_NO_SPEED = "no line speed paints"


@dataclass(frozen=True)
class Cause:
    """Why a plan was refused, sorted (:func:`cause_of`).

    Attributes
    ----------
    binding : str
        The constraint that binds, one of :data:`BINDINGS`.
    said : str
        Its figure in a few words: "motor 126 % at any speed", "bottom band 40 mm short of
        the run-on", "23 of 46 turnarounds and first ramp out of reach".
    short : str
        Fewer words: "motor 126 %", "bottom band 40 mm short", "turnarounds out of reach".
    robot : str or None
        The robot the refusal names first (None: the cell's or the job's).
    message : str
        The refusal in full.
    speeds : tuple of float or None
        The line speeds [m/s] a ``line speed`` refusal names as painting, (low, high)
        (None: it names none).
    """

    binding: str
    said: str
    short: str
    robot: str | None
    message: str
    speeds: tuple[float, float] | None = None

    def past_speeds(self, speed: float, factor: float) -> bool:
        """Whether ``speed`` [m/s] lies more than ``factor`` times past the interval of line
        speeds this refusal names as painting (over its top, or under its bottom where that
        is not "or slower"); False when it names none."""
        if self.speeds is None:
            return False
        low, high = self.speeds
        slower = "or slower" in self.said
        return speed > factor * high or (not slower and speed * factor < low)


def binding_of(message: str) -> str:
    """The constraint a planner's refusal names: ``clearance``, ``motors``, ``reach``,
    ``film``, or ``plan`` when its words name none of them."""
    m = message.lower()
    return next((name for word, name in _WORDS if word in m), "plan")


def _mm(a: str, b: str) -> str:
    return f"{abs(float(b) - float(a)) * 1e3:.0f} mm"


def _band_end(m):
    side = {"lowest": "bottom", "highest": "top"}[m[3]]
    return f"{side} band {_mm(m[1], m[2])} short of the run-on", \
        f"{side} band {_mm(m[1], m[2])} short"


def _gap(m):
    return f"{_mm(m[1], m[2])} between two bands unreached", f"gap {_mm(m[1], m[2])}"


def _overlap(m):
    return (f"bands overlap {m[1]} mm, under the {m[2]} mm of a seam's run-outs",
            f"overlap {m[1]} mm short of {m[2]} mm")


def _off_passes(m):
    words = m[1].replace("its ", "")
    kind = ("turnarounds" if "turnaround" in words else
            "ramps" if words.count("ramp") > 1 else "ramp")
    return f"{words} out of reach", f"{kind} out of reach"


def _passes(m):
    tall = re.search(r"(\d+) mm too (tall|long)", m.string)
    return (m[1] + " out of reach" + (f", {tall[1]} mm too {tall[2]}" if tall else ""),
            "passes out of reach")


def _speeds(said: str) -> tuple[float, float] | None:
    """(low, high) [m/s] of an interval said "0.0156–0.0459 m/s" (one speed: both)."""
    values = [float(v) for v in re.findall(r"\d+(?:\.\d+)?(?:e-?\d+)?", said)]
    return (values[0], values[-1]) if values else None


def _motor(m):
    use = max(float(u) for u in re.findall(r"motor at " + _NUMBER + " %", m.string))
    anywhere = " at any speed" if _NO_SPEED in m.string else ""
    return f"motor {use:.4g} %{anywhere}", f"motor {use:.4g} %"


def _no_speed(m):
    low = m.string.lower()
    what = ("drifts out of reach" if "drifts" in low else
            "turnarounds out of reach" if "turnaround" in low else "")
    return (f"{what} at any speed", what) if what else ("no line speed paints it",
                                                        "no line speed")


def _clearance(m):
    who = "robots" if m.string.startswith("robots") else "gun"
    what = "the part" if "the part" in m.string else "each other"
    gap = f"{m[1]} mm into" if m[2] else f"within {m[1]} mm"
    return f"{who} {gap} {'of ' if not m[2] else ''}{what}", f"clearance {gap}"


# (binding or None: binding_of's, the words, their figure in words (said, short)), first match
_RULES = (
    ("band", r"no robot reaches .*?" + _NUMBER + "…" + _NUMBER + r" m \(the part's edge [^;]*; "
     r"the (lowest|highest) band", _band_end),
    ("band", r"no robot reaches .*?" + _NUMBER + "…" + _NUMBER + r" m between robots", _gap),
    ("band", r"overlap along .*? by (-?\d+) mm .*?less than the (\d+) mm", _overlap),
    ("band", r"no zone of at least (\d+) mm",
     lambda m: (f"no room for a zone of {m[1]} mm", "band holds no zone")),
    ("band", r"each zone needs " + _NUMBER + r" m .*?a robot's band is " + _NUMBER + " m",
     lambda m: (f"band {_mm(m[1], m[2])} short", f"band {_mm(m[1], m[2])} short")),
    ("reach", r"no place on the line keeps (.+?) in reach", _off_passes),
    ("reach", r"(all \d+ passes|pass(?:es)? [^:]*? of \d+) out of reach at any place", _passes),
    ("reach", r"never comes within reach", lambda m: ("never in reach", "never in reach")),
    ("line speed", r"it paints at (\S+ m/s)( or slower)?",
     lambda m: (f"paints only at {m[1]}{m[2] or ''}", f"paints at {m[1]}")),
    ("motors", r"motor at " + _NUMBER + " %", _motor),
    (None, _NO_SPEED, _no_speed),
    ("motors", r"motor (\S+) runs at " + _NUMBER + " % of its continuous",
     lambda m: (f"motor {m[1]} {float(m[2]):.4g} % RMS", f"motor {float(m[2]):.4g} % RMS")),
    ("clearance", r"\b(?:come|cut)s? (?:within )?(\d+(?:\.\d+)?) mm( into)?", _clearance),
    ("clearance", r"(\d+) mm apart, closer than",
     lambda m: (f"bases {m[1]} mm apart", f"bases {m[1]} mm apart")),
)
_COMPILED = tuple((b, re.compile(w), f) for b, w, f in _RULES)


def cause_of(message: str) -> Cause:
    """The constraint a planner's refusal names and its figure (the module's help).

    Parameters
    ----------
    message : str
        The refusal, one line (a job's path before it dropped or not).

    Returns
    -------
    Cause
        Its binding constraint, its figure in words, the robot it names.

    Examples
    --------
    >>> c = cause_of("robot 'robot1': no place on the line keeps its first ramp in reach (its "
    ...              "passes each fit): move the robot or the part")
    >>> c.binding, c.said, c.robot
    ('reach', 'first ramp out of reach', 'robot1')
    """
    text = " ".join(str(message).split())
    robot = _ROBOT.match(text)
    body = text[robot.end():] if robot else text
    for binding, words, figure in _COMPILED:
        m = words.search(body)
        if m:
            said, short = figure(m)
            speeds = _speeds(m[1]) if binding == "line speed" else None
            return Cause(binding or binding_of(body), said, short, robot and robot[1], text,
                         speeds)
    said = without_asides(body).split("; ")[0]
    return Cause(binding_of(body), said, said.split(": ")[0], robot and robot[1], text)


def search_refusal(source: str, causes: dict, first: int, speed: float | None,
                   levered: dict | None = None) -> str:
    """The layout search's refusal, one line: the counts tried and each one's cause (the
    plain proposal's; ``levered``: count → the cause with the levers, said beside the plain
    one where it differs), the longest said with less (its figure, fewer words, its
    constraint alone) until the line holds them all; the counts whose bands are too narrow
    said together."""
    levered = levered or {}
    last = max(causes)
    head = (f"{source}: no cell of {'1–' if last > 1 else ''}{last} robots paints the part "
            + (f"at {speed:.4g} m/s" if speed is not None else "at any line speed")
            + (" (its levers too): " if levered else ": "))

    def row(n):
        c, lever = causes[n], levered.get(n)
        if lever is None or lever.said == c.said:
            return str(n), c.said, c.short, c.binding
        return (str(n), f"{c.said} (levers: {lever.said})", f"{c.short} (levers: "
                f"{lever.short})", c.binding if lever.binding == c.binding else
                f"{c.binding} (levers: {lever.binding})")

    rows = [row(n) for n in range(first, last + 1)]
    if first > 1:  # the narrowest shortfall, the fewest robots' (first − 1)
        c = causes[first - 1]
        more = "band ≥ " if first > 2 else "band "
        rows.insert(0, ("1" if first == 2 else f"1–{first - 1}",
                        c.said.replace("band ", more, 1), c.short.replace("band ", more, 1),
                        c.binding))
    # one cause at a time said with less: each in fewer words (the longest first) before any
    # is its constraint alone
    said, versions = [1] * len(rows), []
    while True:
        versions.append(head + "; ".join(f"{r[0]} {r[k]}" for r, k in zip(rows, said)))
        left = [i for i, k in enumerate(said) if k < 3]
        if not left:
            return say_less(*versions)
        i = max(left, key=lambda i: (-said[i], len(rows[i][said[i]]), -i))
        said[i] += 1


__all__ = ["BINDINGS", "Cause", "binding_of", "cause_of", "search_refusal"]
