"""
Designing the robot for a paint line
====================================

The thesis robot reaches a band about 0.3 m tall at the spraying standoff, so a cabinet door
0.38 m tall takes two of them. ``pollard-pin design`` asks the builder's question the other way
round: which lengths, joint ranges and motors paint the door *with one robot*, at the line's
speed? A design space says what may change; each design is made concrete under a mass model
(longer links are heavier), screened cheaply, then planned in full (docs/model.md §31). The
command line: ``pollard-pin design --job J.toml --space S.toml --out DIR --trials N``.
"""

# %%
# The job and the design space
# ----------------------------
# ``examples/design/job.toml``: a door 0.80 × 0.38 m, its face 0.70 m out, riding the line at
# 0.012 m/s. ``examples/design/space.toml``: the arms and the links each scaled by a factor in
# [1, 1.8], θ21's upper limit, one motor and gear ratio for the base and one for the wrist
# from an *illustrative* catalogue (``motors.toml``), the robots standing up to 0.4 m back, one
# to three of them. Each variable is what the optimiser samples.
import tempfile
import time
import warnings
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import pollard_pin as pp
from pollard_pin.synthesis import (
    DesignOptions,
    baseline_values,
    build,
    evaluate,
    load_space,
    prepare,
    space_from_dict,
)


def _examples() -> Path:
    """examples/design/, beside docs/ (the gallery runs this file from docs/tutorials)."""
    here = Path(__file__).resolve().parent if "__file__" in globals() else Path.cwd()
    for folder in (here, *here.parents):
        if (folder / "examples" / "design" / "job.toml").is_file():
            return folder / "examples" / "design"
    raise FileNotFoundError("examples/design/ not found above this tutorial")


EXAMPLES = _examples()
job = pp.load_job(EXAMPLES / "job.toml")
space = load_space(EXAMPLES / "space.toml")
print(f"door {job.width} × {job.height} m at {job.line.speed} m/s")
for v in space.variables():
    what = (", ".join(str(c) for c in v.choices) if v.kind == "categorical"
            else f"{v.low:g} .. {v.high:g}")
    print(f"  {v.name:22s} {v.kind:12s} {what}")

# %%
# The thesis robot as a design
# ----------------------------
# ``baseline_values`` is the thesis robot in the space's terms: every factor 1, θ21's limit at
# today's value, the catalogue motors nearest the shipped ones (S20 at the base, W5 at the
# wrist), standing at the origin, one robot. The scaled design below changes four values:
# both factors 1.7, the S100 motor at the base, and 0.3 m further back.
thesis = baseline_values(space)
scaled = dict(thesis, **{"scale.arms": 1.7, "scale.links": 1.7, "place.back": 0.3,
                         "motor.base": space.catalogue.names.index("S100")})
for name, values in (("thesis", thesis), ("scaled", scaled)):
    d = build(values, space)
    motors = sorted({f"{m} ×{n:g}" for m, n in d.motors.values()})
    print(f"{name}: x32 = {d.params.x32:.3f} m, x65 = {d.params.x65:.3f} m; motors "
          f"{', '.join(motors)}")

# %%
# The mass model
# --------------
# A design is never judged with the thesis' masses on longer links (§31.1). Each link keeps its
# section and density and is stretched along its axis by s = L/L_ref: its mass grows as s, its
# transverse inertia as s³. The wrist motors ride on the platform; the base motors stand on the
# base (only their rotors count, through the gear). At s = 1 with the shipped motors it is the
# thesis robot plus the wrist motors' 0.12 kg.
scales = np.linspace(1.0, 1.8, 9)
bodies = ("arm0", "platform", "link_1")
rows = []
for s in scales:
    d = build(dict(thesis, **{"scale.arms": s, "scale.links": s}), space, check_home=False)
    b = d.toml["bodies"]
    rows.append([d.moving_mass] + [b[k]["mass"] for k in bodies]
                + [b["arm0"]["inertia"][2][2] * 1e-6])
rows = np.array(rows)
for s, r in zip(scales[[0, 4, 7]], rows[[0, 4, 7]]):
    print(f"s = {s:.1f}: moving mass {r[0]:.3f} kg (arm0 {r[1]:.3f}, platform {r[2]:.3f}, "
          f"link_1 {r[3]:.3f} kg); arm0 I_zz {r[4] * 1e3:.2f} g·m²")

fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(9, 3.6))
ax0.plot(scales, rows[:, 0], "k-o", label="moving mass (one robot)")
for i, name in enumerate(bodies, start=1):
    ax0.plot(scales, rows[:, i], "--", label=name)
ax0.set(xlabel="length factor s (arms and links)", ylabel="mass [kg]",
        title="masses follow the lengths")
ax0.legend(fontsize=8)
ax1.plot(scales, rows[:, 4] / rows[0, 4], "C3-o", label="arm0 transverse inertia")
ax1.plot(scales, scales ** 3, "k:", label="s³")
ax1.plot(scales, rows[:, 1] / rows[0, 1], "C0-o", label="arm0 mass")
ax1.set(xlabel="length factor s", ylabel="over today's", title="the law: m ∝ s, I ∝ s³")
ax1.legend(fontsize=8)
fig.tight_layout()

# %%
# The screen: why the thesis robot needs two
# ------------------------------------------
# The screen (``level="screen"``) rejects what cannot work, in milliseconds: the robot's band
# along the cell's axis over the door's middle stroke (the planner's own rule: closed-form IK,
# joint limits, singularity margins, on a coarse grid), against what one robot's zone needs
# (the door, two 4σ run-ons and, past them, the run-on of the program's turnarounds and ramps:
# the planner's own raster, ``turn_runon``), and the torques that hold the robot still against
# the motors' ratings. ``prepare`` builds what every evaluation shares.
ctx = prepare(job, space)


def screened(values):
    t0 = time.process_time()
    ev = evaluate(values, ctx, "screen")
    return ev, (time.process_time() - t0) * 1e3


for name, values in (("thesis", thesis), ("scaled", scaled)):
    ev, ms = screened(values)
    need = ev.constraints["reach"] + ev.figures["band_m"]
    print(f"{name}: band {ev.figures['band_m']:.2f} m against {need:.2f} m for one robot "
          f"(robots needed: {ev.figures['robots_needed']}); static motor use "
          f"{ev.objectives['motor_use']:.2f}; {'passes' if ev.feasible else 'fails: '}"
          f"{ev.binding or ''} ({ms:.0f} ms CPU)")

# %%
# The band against the length factor, at the origin and 0.3 m back: a longer robot reaches a
# taller band, but only if it also stands back from the door (its reach ball is bigger; at the
# origin the door's face sits too close to its centre).
bands = {}
for back in (0.0, 0.3):
    bands[back] = [screened(dict(thesis, **{"scale.arms": s, "scale.links": s,
                                            "place.back": back,
                                            "motor.base": scaled["motor.base"]}))[0]
                   for s in scales]
fig, ax = plt.subplots(figsize=(6, 3.6))
for back, evs in bands.items():
    ax.plot(scales, [e.figures["band_m"] for e in evs], "-o", label=f"{back:g} m back")
ax.axhline(need, color="k", ls="--", label=f"one robot's zone ({need:.2f} m)")
ax.set(xlabel="length factor s (arms and links)", ylabel="band [m]",
       title="the screen's band over the door's stroke")
ax.legend(fontsize=8)
fig.tight_layout()

# %%
# The full evaluation: one scaled robot against two thesis robots
# ---------------------------------------------------------------
# A design that passes the screen is planned in full (``level="full"``): the robots placed as
# ``paint --robots N`` places them, the door painted at the line's 0.012 m/s with the design's
# parameters and motors, then its film, the motors' use over the program, the clearances and
# the least tip stiffness kmin (docs/model.md §27). The thesis robot alone fails the screen,
# so its baseline here is the cell of two.
full = {}
for name, values in (("thesis, 2 robots", dict(thesis, robots=2)),
                     ("×1.7, S100, 0.3 m back, 1 robot", scaled)):
    t0 = time.process_time()
    full[name] = evaluate(values, ctx, "full")
    full[name].figures["cpu_s"] = time.process_time() - t0
print(f"{'design':34s} {'robots':>6s} {'parts/h':>8s} {'motor use':>9s} {'kmin N/m':>9s} "
      f"{'mass kg':>8s} {'film µm':>13s} {'CPU s':>6s}")
for name, ev in full.items():
    o, f = ev.objectives, ev.figures
    print(f"{name:34s} {o['robots']:6.0f} {o['parts_per_hour']:8.1f} {o['motor_use']:9.3f} "
          f"{o['kmin']:9.0f} {o['moving_mass']:8.2f} "
          f"{f['film_min_um']:6.2f}–{f['film_max_um']:5.2f} {f['cpu_s']:6.1f}")
    assert ev.feasible, ev.binding

# %%
# One robot paints the door alone at the same line speed, a little faster per part (its cycle
# is shorter), stiffer at the tip and lighter than the cell of two. Its files are what every
# command takes: ``paint --params params.toml --actuators actuators.toml`` with the
# ``[[robot]]`` table of ``robots.toml`` added to the job reproduces these figures.
ev = full["×1.7, S100, 0.3 m back, 1 robot"]
print(ev.robots_toml[ev.robots_toml.index("\n[[robot]]") + 1:])
print("\n".join(ev.actuators_toml.splitlines()[:10]))

# %%
# A study
# -------
# ``pp.design(job, space, options)`` searches the space with optuna's NSGA-II, the thesis robot as
# its first design (the baseline row). NSGA-II's first generation would be random, and one-robot
# designs are a thin slab of the space (both factors near 1.7, a strong enough base motor, about 0.3
# m back), so a new study first screens a *ladder* (every length factor together in 9 steps, the
# place in 5, each catalogue motor of a group in turn, the robot count up to the first the screen
# passes: milliseconds each) and starts with the best it passes, the fewest robots first
# (docs/model.md §31.5). Every design is screened and, when it passes, planned in full;
# ``DesignOptions(screen_only=True)`` judges the study by the screen alone and plans only its front
# in full at the end. The front is told apart at each objective's resolution
# (``DesignOptions(front=FrontResolution(...))``: parts per hour 1 %, motor use 0.01, kmin 10 %,
# moving mass 2 %; all 0: the exact Pareto front), so designs closer than that are planned
# again and shown once (a 200-evaluation study of the example: 18 of its 46).
# ``study="DIR/study.db"`` keeps every finished evaluation in a SQLite file (``resume=True``
# continues it); ``result.write(DIR)`` writes the chosen design's files,
# ``front.csv``, ``trials.parquet`` and ``front.png``. The command line
# does the same, on every core::
#
#     pollard-pin design --job examples/design/job.toml --space examples/design/space.toml \
#         --out study --trials 200
#
# Here a quick look that fits this page: the space narrowed to one robot, one length factor
# in [1.7, 1.8] for the arms and the links together, 0.3–0.4 m back, and a catalogue of two
# motors (S100 behind 100:1, W5 behind 50:1) for the base and for the wrist; its ladder
# screened, then 12 designs screened in this process (the thesis robot and the ladder's best
# 11), then the front planned in full. On the example's whole space the ladder's first
# generation already holds the one-robot designs (docs/model.md §31.5).
folder = Path(tempfile.mkdtemp())
text = (EXAMPLES / "motors.toml").read_text()
two = [t for t in text.split("\n[motors.") if t.startswith(("S100]", "W5]"))]
(folder / "motors.toml").write_text("".join(
    "[motors." + t.replace("ratios = [50, 100, 160]", "ratios = [100]")
    .replace("ratios = [50, 100]", "ratios = [50]") + "\n" for t in two))
small = space_from_dict({
    "catalogue": "motors.toml", "robots": 1,
    "scale": [{"name": "size", "range": [1.7, 1.8],
               "keys": ["chain0.x32", "leg1.x43", "leg2.x43", "chain0.x65", "leg1.x87",
                        "leg2.x87"]}],
    "motors": {"base": ["theta21", "theta21_1", "theta21_2"],
               "wrist": ["theta1615", "theta1716", "theta1817"]},
    "place": {"back": [0.3, 0.4]}}, "narrowed space", folder)
print([v.name for v in small.variables()])
# the study's first design is the thesis robot (factor 1), outside this narrowed range on
# purpose: optuna says so in a warning, and the screen refuses it (its band)
warnings.filterwarnings("ignore", message="Fixed parameter", category=UserWarning)
t0 = time.process_time()
result = pp.design(job, small, DesignOptions(trials=12, workers=1, screen_only=True, seed=0))
print(f"{time.process_time() - t0:.1f} s CPU")
print("\n".join(result.summary_lines()))

# %%
# ``result.write(DIR)`` writes what the command writes: the chosen design's files (every
# command takes them), ``front.csv`` with the thesis robot as row 0, ``trials.parquet`` with
# every evaluation, and ``front.png``.
out = result.write(folder / "study")
print(sorted(p.name for p in out.iterdir()))
print((out / "front.csv").read_text().splitlines()[0])

# %%
# Every evaluation of the study in the plane of its two continuous variables: the ladder's
# designs the screen passed, and the thesis robot it refuses (its band); the screen refuses a
# design for its motors (``motors_static``: a W5 at the base, or three S100, 2.7 kg, riding
# on the platform) before any plan. A design
# that passes the screen may still be refused by the full plan: the study's note above names
# it and why; the front holds only designs judged by their full plan.
fig, ax = plt.subplots(figsize=(7.5, 3.6))
for ok, marker in ((False, "x"), (True, "o")):
    rows = [r for r in result.trials if r["feasible"] == ok and r["scale.size"] >= 1.7]
    ax.scatter([r["scale.size"] for r in rows], [r["place.back"] for r in rows],
               marker=marker, label="passes the screen" if ok else "refused by the screen")
print({b: sum(r["binding"] == b for r in result.trials)
       for b in sorted({r["binding"] for r in result.trials if r["binding"]})})
for d in result.front:
    v, o = d["values"], d["objectives"]
    ax.scatter([v["scale.size"]], [v["place.back"]], marker="*", s=200, color="C2",
               label=f"front design {d['design']}: {o['parts_per_hour']:.1f} parts/h, "
                     f"{o['moving_mass']:.2f} kg")
ax.set(xlabel="length factor s (arms and links)", ylabel="standing back [m]",
       title=f"a {len(result.trials)}-design study of the door, one robot")
ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.02, 1.0))
fig.tight_layout()
plt.show()
