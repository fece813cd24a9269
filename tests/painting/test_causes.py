"""A planner's refusal sorted by the constraint that binds, with its figure
(painting/causes.py, docs/model.md §26.5): each refusal as its raise site words it."""
import pytest

from pollard_pin.painting.causes import BINDINGS, Cause, binding_of, cause_of

# (refusal, binding, said, short)
REFUSALS = [
    ("no robot reaches z -0.015…0.025 m (the part's edge 0.015 m and its run-on; the lowest "
     "band starts at 0.025 m, robot 'robot1')", "band", "bottom band 40 mm short of the run-on",
     "bottom band 40 mm short"),
    ("no robot reaches z 0.320…0.375 m (the part's edge 0.345 m and its run-on; the highest "
     "band ends at 0.320 m, robot 'robot3')", "band", "top band 55 mm short of the run-on",
     "top band 55 mm short"),
    ("no robot reaches z 0.280…0.340 m between robots 'low' (up to 0.280 m) and 'high' (from "
     "0.340 m)", "band", "60 mm between two bands unreached", "gap 60 mm"),
    ("robots 'low' and 'high' overlap along z by 40 mm (0.240…0.280 m), less than the 80 mm a "
     "seam's run-outs need (R = 40 mm each side)", "band",
     "bands overlap 40 mm, under the 80 mm of a seam's run-outs", "overlap 40 mm short of 80 mm"),
    ("the bands leave robot 'mid' (z 0.200…0.300 m) no zone of at least 20 mm with its "
     "run-outs (40 mm past each seam) between its neighbours' seams", "band",
     "no room for a zone of 20 mm", "band holds no zone"),
    ("2 robot(s) cannot paint the part: each zone needs 0.420 m along z with its run-outs, a "
     "robot's band is 0.340 m (at least 3 robots)", "band", "band 80 mm short",
     "band 80 mm short"),
    ("robot 'robot1': no place on the line keeps its first ramp and its last ramp in reach (its "
     "passes each fit): move the robot or the part", "reach",
     "first ramp and last ramp out of reach", "ramps out of reach"),
    ("robot 'robot2': no place on the line keeps 23 of its 46 turnarounds and its first ramp in "
     "reach (its passes each fit): move the robot or the part", "reach",
     "23 of 46 turnarounds and first ramp out of reach", "turnarounds out of reach"),
    ("passes 3–5 of 12 out of reach at any place on the line: pass 4 is 0.900 m (run-on "
     "included), at most 0.700 m of it in reach, 200 mm too long for the reach: turn, move or "
     "split the part", "reach", "passes 3–5 of 12 out of reach, 200 mm too long",
     "passes out of reach"),
    ("the part never comes within reach: y 0.1…0.4 m; none of its 9 passes is in reach within "
     "0..1 m of travel: move the part or the line", "reach", "never in reach", "never in reach"),
    ("at line speed 0.024 m/s the program drifts +0.300 m along the line in 12.5 s and leaves "
     "the reach wherever it starts; it paints at 0.0031–0.0202 m/s (--max-line-speed)",
     "line speed", "paints only at 0.0031–0.0202 m/s", "paints at 0.0031–0.0202 m/s"),
    ("no line speed paints the part: too slow at 0.03394 m/s (a motor at 126 % of its rating), "
     "too fast at 0.03413 m/s (a motor at 131.5 % of its rating); binding: slow (motors), fast "
     "(motors)", "motors", "motor 131.5 % at any speed", "motor 131.5 %"),
    ("at line speed 0.05 m/s a motor at 108 % of its rating (its peak torque)", "motors",
     "motor 108 %", "motor 108 %"),
    ("no line speed paints the part: too slow at 0.01 m/s (the program drifts -0.349 m, out of "
     "the reach), too fast at 0.02 m/s (the program drifts +0.2 m, out of the reach); binding: "
     "slow (reach), fast (reach)", "reach", "drifts out of reach at any speed",
     "drifts out of reach"),
    ("motor m3 runs at 112.5 % of its continuous (RMS) torque over the cycle (docs/model.md "
     "§19): the cycle repeats, so it would overheat", "motors", "motor m3 112.5 % RMS",
     "motor 112.5 % RMS"),
    ("robots 'low' and 'high' come within 3 mm at t = 0.00 s (clearance 10 mm, ± 1.0 mm between "
     "samples): move a base further along the line", "clearance",
     "robots within 3 mm of each other", "clearance within 3 mm"),
    ("robots 'low' and 'high' cut 4 mm into each other at t = 0.00 s", "clearance",
     "robots 4 mm into each other", "clearance 4 mm into"),
    ("robot 'low' cuts 12 mm into the part at t = 1.50 s (clearance 10 mm, ± 1.0 mm between "
     "samples)", "clearance", "gun 12 mm into the part", "clearance 12 mm into"),
    ("robot 'r1': the gun's body comes 1.2 mm from the part at (1, 2, 3) mm, t = 0.500 s; "
     "clearance 10 mm: a larger standoff", "clearance", "gun within 1.2 mm of the part",
     "clearance within 1.2 mm"),
    ("robots 'a' and 'b' stand 168 mm apart, closer than a robot's own base (2 × 85 mm)",
     "clearance", "bases 168 mm apart", "bases 168 mm apart"),
]


@pytest.mark.parametrize("message, binding, said, short", REFUSALS,
                         ids=[r[0][:30] for r in REFUSALS])
def test_each_refusal_names_its_constraint_and_figure(message, binding, said, short):
    cause = cause_of(message)
    assert (cause.binding, cause.said, cause.short) == (binding, said, short)
    assert cause.binding in BINDINGS and cause.message == message


def test_the_figure_is_the_refusals():
    a = cause_of("no robot reaches z -0.015…0.025 m (the part's edge 0.015 m and its run-on; "
                 "the lowest band starts at 0.025 m, robot 'robot1')")
    b = cause_of("no robot reaches z -0.015…0.100 m (the part's edge 0.015 m and its run-on; "
                 "the lowest band starts at 0.100 m, robot 'robot1')")
    assert (a.short, b.short) == ("bottom band 40 mm short", "bottom band 115 mm short")


def test_the_robot_named_first_is_kept_apart():
    cause = cause_of("robot 'r 2': no place on the line keeps its first ramp in reach (its "
                     "passes each fit): move the robot or the part")
    assert cause == Cause("reach", "first ramp out of reach", "ramp out of reach", "r 2",
                          cause.message)
    assert cause_of("no place on the line keeps its first ramp in reach").robot is None


def test_words_it_does_not_know_keep_their_first_clause():
    cause = cause_of("robot 'x': the film misses: 12 % of the area (thin at the edges) under "
                     "target; paint slower")
    assert cause == Cause("film", "the film misses: 12 % of the area under target",
                          "the film misses", "x", cause.message)
    assert cause_of("something else entirely").binding == "plan"


@pytest.mark.parametrize("message, binding", [
    ("the gun's body comes closer than 5 mm to the part", "clearance"),
    ("robots 'a' and 'b' 300.0 mm apart at their closest", "clearance"),
    ("peak torque over the rating", "motors"),
    ("a motor at 120 %", "motors"),
    ("pose out of reach at sample 4", "reach"),
    ("joint 3 past its limit", "reach"),
    ("a singular pose", "reach"),
    ("the film is thin", "film"),
    ("over the sample budget", "plan")])
def test_binding_of_in_the_design_studys_words(message, binding):
    """The design study's constraint (synthesis/evaluation.py), first word that names one."""
    assert binding_of(message) == binding


@pytest.mark.parametrize("message, speeds, past", [
    ("at line speed 0.5 m/s it drifts; it paints at 0.01562–0.0459 m/s or slower "
     "(--max-line-speed)", (0.01562, 0.0459), {0.5: True, 0.09: False, 0.0001: False}),
    ("line speed 0.001 m/s: it paints at 0.003–0.04 m/s (--max-line-speed)", (0.003, 0.04),
     {0.001: True, 0.0016: False, 0.08: False, 0.0801: True}),
    ("line speed 1e-05 m/s: it paints at 2.5e-05–0.0459 m/s (--max-line-speed)",
     (2.5e-05, 0.0459), {1e-05: True, 2e-05: False}),
    ("robot 'a': no place on the line keeps its first ramp in reach", None, {9.0: False}),
])
def test_the_speeds_a_refusal_names_and_a_speed_past_them(message, speeds, past):
    """A line-speed refusal's interval read back from its words (as line.speeds says it,
    with exponents); a speed more than twice past it: over the top, or under the bottom
    unless the slow end is "or slower"; a refusal naming no interval is past nothing."""
    c = cause_of(message)
    assert c.speeds == speeds
    assert {v: c.past_speeds(v, 2.0) for v in past} == past
