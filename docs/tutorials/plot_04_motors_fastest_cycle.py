"""
Sizing motors and the fastest cycle
===================================

Put a motor and a gearbox on each actuator, check them on the thesis path, and ask how fast
the same path can run: uniformly time-scaled, and time-optimally by TOPP-RA under the peak
torque and speed limits (docs/model.md §19). The command line does the same with
``pollard-pin size --actuators FILE.toml``.
"""

# %%
# The motors
# ----------
# One TOML table per actuator joint, motor side, SI units: the gear ratio N (motor angle =
# N × joint angle), rotor inertia, viscous and Coulomb friction, peak and continuous (RMS)
# torque, maximum speed. Here small servo motors behind 100:1 (base) and 50:1 (wrist).
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import pollard_pin as pp

base = """gear_ratio = 100.0
rotor_inertia = 5e-6
viscous = 1e-6
coulomb = 1e-3
peak_torque = 0.05
continuous_torque = 0.02
max_speed = 500.0
"""
wrist = base.replace("100.0", "50.0").replace("5e-6", "1e-6").replace("0.05", "0.01") \
    .replace("0.02", "0.004")
text = "".join(f"[{name}]\n{base if name.startswith('theta21') else wrist}\n"
               for name in ("theta21", "theta21_1", "theta21_2",
                            "theta1615", "theta1716", "theta1817"))
path = Path(tempfile.mkdtemp()) / "actuators.toml"
path.write_text(text)
act = pp.load_actuators(path)
print(act.names)
print(act["theta21"])

# %%
# Size them on the thesis path
# ----------------------------
# :func:`pollard_pin.actuator_sizing` takes a pipeline result; its ``report`` is what
# ``pollard-pin size --format json`` prints: per motor, peak and RMS torque and peak speed
# with their ratios to the ratings, then the shortest uniform and time-optimal cycles.
robot = pp.load()
traj = pp.thesis_trajectory(duration=20.0, samples=201)
result = pp.run_pipeline(robot, traj)
sizing = pp.actuator_sizing(robot, result, act)
report = sizing.report
print("within the ratings at 20 s:", report["given_within_ratings"])
for name, row in report["actuators"].items():
    ratios = {k: round(v, 3) for k, v in row.items() if k.endswith("_ratio") and k != "gear_ratio"}
    print(f"  {name:10s} {ratios}")
print(f"uniform scaling: {report['uniform_min_duration']:.2f} s "
      f"({report['uniform_binding']})")
print(f"time-optimal (TOPP-RA): {report['time_optimal_duration']:.2f} s")

# %%
# The time-optimal traversal
# --------------------------
# :func:`pollard_pin.time_optimal_path` gives the traversal itself (a
# :class:`pollard_pin.dynamics.TimeOptimal`): at each point s of the path (0 to 1), its time, path
# rate ṡ and path acceleration s̈. The motors run at a peak torque or full speed most of
# the time, which is what makes it the fastest.
timing = pp.time_optimal_path(robot, act, traj)
print(f"{timing.t[-1]:.3f} s; worst use of a limit between the samples {timing.between:.4f}")

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 3.6))
ax1.plot(timing.s, timing.s_dot)
ax1.set_xlabel("s (path parameter)")
ax1.set_ylabel("ṡ [1/s]")
ax1.set_title("path rate, rest to rest")
ax2.plot(traj.t / traj.t[-1], traj.t, label="thesis timing (20 s)")
ax2.plot(timing.s, timing.t, label=f"time-optimal ({timing.t[-1]:.1f} s)")
ax2.set_xlabel("s")
ax2.set_ylabel("t [s]")
ax2.legend()
fig.tight_layout()

# %%
# Motor torques of the fastest cycle
# ----------------------------------
# ``sizing.optimal`` holds the motor-side torque τm = τ/N + Jm·N·q̈ + b·N·q̇ + c·sign(q̇)
# along the time-optimal cycle; each base motor touches its peak rating. TOPP-RA bounds the
# peak torque and speed only: run back to back, this cycle would heat the base motors past
# their continuous (RMS) rating, which the report's ``time_optimal_rms_motor_torque_ratio``
# says (above 1). The uniformly scaled cycle is the shortest that keeps the RMS too.
opt = sizing.optimal
fig, ax = plt.subplots(figsize=(7, 3.6))
for j, name in enumerate(act.names[:3]):
    ax.plot(opt.t, opt.torque[:, j] / act[name].peak_torque, label=name)
ax.axhline(1.0, color="k", lw=0.8)
ax.axhline(-1.0, color="k", lw=0.8)
ax.set_xlabel("t [s]")
ax.set_ylabel("τm / peak torque")
ax.legend(fontsize=8)
fig.tight_layout()
plt.show()
print("peak torque use:", np.round(opt.peak_torque / act.column("peak_torque"), 3))
print("RMS torque use:", np.round(opt.rms_torque / act.column("continuous_torque"), 2))
