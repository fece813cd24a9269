"""
Stiffness and vibration
=======================

How far does the gun give under load, and how low are the modes? Each drive (motor and
gearbox) is a torsional spring of stiffness kᵢ [N·m/rad] at its joint, the links rigid
(docs/model.md §27): the compliance C = J K⁻¹ Jᵀ, the deflection under a wrench and the
robot's own weight, the six natural frequencies from K u = ω² Mₐ u, and kmin, the tip's
stiffness in its softest direction. The springs then replace the rigid drives in the
closed-loop simulation (§28). The command line: ``pollard-pin stiffness --trajectory FILE.csv
--actuators FILE.toml [--wrench=FX,FY,FZ,MX,MY,MZ]``.
"""

# %%
# The drives' stiffness
# ---------------------
# Each drive's ``stiffness`` [N·m/rad, joint side] is a key of its actuators TOML table; these
# are ``examples/actuators.toml``'s: 3000 at the 100:1 base drives, 300 at the 50:1 wrist ones.
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import pollard_pin as pp
from pollard_pin.dynamics import ModelMismatch
from pollard_pin.dynamics.drives import FlexibleDrives, deflection_at, stiffness_at

base = """gear_ratio = 100.0
rotor_inertia = 5e-6
viscous = 1e-6
coulomb = 1e-3
peak_torque = 0.05
continuous_torque = 0.02
max_speed = 500.0
stiffness = 3000.0
"""
wrist = """gear_ratio = 50.0
rotor_inertia = 1e-6
viscous = 5e-7
coulomb = 2e-4
peak_torque = 0.01
continuous_torque = 0.004
max_speed = 800.0
stiffness = 300.0
"""
path = Path(tempfile.mkdtemp()) / "actuators.toml"
path.write_text("".join(f"[{name}]\n{base if name.startswith('theta21') else wrist}\n"
                        for name in ("theta21", "theta21_1", "theta21_2",
                                     "theta1615", "theta1716", "theta1817")))
robot = pp.load()
actuators = pp.load_actuators(path)
k = actuators.stiffness()
print("k [N·m/rad]:", {n: float(v) for n, v in zip(actuators.names, k)})

# %%
# At home: compliance, sag and a 5 N tip force
# --------------------------------------------
# At home (x = 0.55, y = 0, z = 0.16 m, the gun along +x) the inverse kinematics gives the
# closed configuration. ``deflection_at`` is linear in the wrench (force at the tip, moment
# about it, world axes): its change under a unit force is a column of the compliance C.
home = np.array([[0.55, 0.0, 0.16, 0.0, 0.0, 0.0]])
q = pp.inverse_kinematics(robot, home).q
sag = deflection_at(robot, q, k)[0]
C = np.column_stack([deflection_at(robot, q, k, np.eye(6)[i])[0] - sag for i in range(3)])
print("compliance C[:3, :3] [µm/N]:\n", (C[:3] * 1e6).round(2))
print("sag under the weight: d =", (sag[:3] * 1e6).round(1), "µm, rotation",
      (sag[3:] * 1e3).round(3), "mrad")
for axis, name in enumerate("xyz"):
    w = np.zeros(6)
    w[axis] = 5.0
    d = deflection_at(robot, q, k, w)[0] - sag
    print(f"5 N along {name}: the tip moves {np.linalg.norm(d[:3]) * 1e6:.0f} µm")
at_home = stiffness_at(robot, q, k)
print("frequencies [Hz]:", at_home.frequencies[0].round(1))
print(f"kmin = {at_home.kmin[0]:.0f} N/m = 1 / λmax(C[:3, :3]) = "
      f"{1 / np.linalg.eigvalsh((C[:3] + C[:3].T) / 2).max():.0f} N/m")

# %%
# Along the thesis path
# ---------------------
# ``pp.stiffness`` solves the path (the IK and its checks are ``run``'s) and returns, per
# sample, the deflection under the weight plus ``StiffnessOptions(wrench)``, the six
# frequencies and kmin; ``.write(path)`` writes what the command writes.
traj = pp.thesis_trajectory(duration=20.0, samples=401)
res = pp.stiffness(robot, traj, actuators)
cols = res.columns()
print(f"sag dz {cols['dz'].min() * 1e6:.0f} … {cols['dz'].max() * 1e6:.0f} µm, "
      f"f1 {cols['f1'].min():.1f} … {cols['f1'].max():.1f} Hz, "
      f"kmin {cols['kmin'].min():.0f} … {cols['kmin'].max():.0f} N/m")

fig, (ax1, ax2, ax3) = plt.subplots(3, 1, figsize=(7, 7), sharex=True)
for i in range(3):
    ax1.plot(res.t, res.deflection[:, i] * 1e6, label=f"d{'xyz'[i]}")
ax1.set_ylabel("sag [µm]")
ax1.legend(fontsize=7)
for i in range(6):
    ax2.semilogy(res.t, res.frequencies[:, i], label=f"f{i + 1}")
ax2.set_ylabel("frequency [Hz]")
ax2.legend(fontsize=7, ncol=3)
ax3.plot(res.t, res.kmin / 1e3)
ax3.set_ylabel("kmin [kN/m]")
ax3.set_xlabel("t [s]")
fig.tight_layout()
plt.show()

# %%
# A stiffness map
# ---------------
# ``map_workspace`` with an actuators file whose drives all have a stiffness adds ``kmin``,
# ``f1`` and ``sag`` at each reachable point of the plane (a coarse 2 cm grid here).
ws = pp.map_workspace(robot, "x=0.55", pp.WorkspaceOptions(resolution=0.02,
                                                           actuators=actuators))
y, z = ws.grid.coordinates(0), ws.grid.coordinates(1)
extent = (y[0], y[-1], z[0], z[-1])
fig, axes = plt.subplots(1, 2, figsize=(9.5, 3.8))
for ax, name, scale, unit in ((axes[0], "kmin", 1e-3, "kN/m"), (axes[1], "f1", 1.0, "Hz")):
    im = ax.imshow(ws.image(name).T * scale, origin="lower", extent=extent, cmap="viridis")
    ax.set_xlim(-0.4, 0.4)
    ax.set_ylim(-0.15, 0.35)
    ax.set_xlabel("y [m]")
    ax.set_ylabel("z [m]")
    fig.colorbar(im, ax=ax, label=f"{name} [{unit}]")
fig.tight_layout()
plt.show()

# %%
# Flexible drives in simulation
# -----------------------------
# ``TrackingOptions(drives=FlexibleDrives.from_actuators(actuators))`` puts the springs
# between the motors (rotor inertia N²Jₘ, the controller) and the joints; the controller reads
# the motor encoders (§28). The controller must know the rotors' inertia and friction
# (``known_losses``, as ``simulate --actuators`` gives it): the motors' 0.05 kg·m² seen from a
# base joint outweighs the links. The rigid run for comparison has the same rotors on rigid
# drives. On a 4 s pass of the thesis path, the tool's tracking error:
short = pp.thesis_trajectory(duration=4.0, samples=201)
rotors = actuators.joint_losses(robot.joint_names)
rigid = pp.simulate_tracking(robot, short, pp.TrackingOptions(
    "feedforward-pd", ModelMismatch(losses=rotors), known_losses=rotors))
flexible = pp.simulate_tracking(robot, short, pp.TrackingOptions(
    "feedforward-pd", drives=FlexibleDrives.from_actuators(actuators), known_losses=rotors))
for name, r in (("rigid", rigid), ("flexible", flexible)):
    s = r.summary()
    print(f"{name:8s} max tip error {s['max_tip_position_error'] * 1e6:.1f} µm, "
          f"RMS {s['rms_tip_position_error'] * 1e6:.1f} µm, {r.steps} RK4 steps")
fig, ax = plt.subplots(figsize=(7, 3.2))
ax.semilogy(rigid.t, rigid.tip_position_error * 1e6, label="rigid drives")
ax.semilogy(flexible.t, flexible.tip_position_error * 1e6, label="flexible drives")
ax.set_xlabel("t [s]")
ax.set_ylabel("tip position error [µm]")
ax.legend(fontsize=8)
fig.tight_layout()
plt.show()
