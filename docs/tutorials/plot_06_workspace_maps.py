"""
Workspace maps
==============

Where can the gun go at one fixed tool orientation? :func:`pollard_pin.map_workspace` checks
every point of a plane grid (or a box) under the rules of a run plus the joint limits, and
names, for each unreachable point, the first rule it breaks (docs/model.md §22). The command
line: ``pollard-pin workspace --plane x=0.55 --out DIR``.
"""

# %%
# A plane in front of the robot
# -----------------------------
# The wall x = 0.55 m, the gun spraying along +x (ψ = θ = φ = 0), on a 1 cm grid.
import matplotlib.pyplot as plt
import numpy as np

import pollard_pin as pp

robot = pp.load()
ws = pp.map_workspace(robot, "x=0.55", pp.WorkspaceOptions(orientation=(0.0, 0.0, 0.0),
                                                           resolution=0.01))
s = ws.summary
print(f"{s['reachable_points']} of {s['grid']['points']} points reachable, "
      f"area {s['area']:.3f} ± {s['area_bound']:.3f} m²")
print(f"global conditioning index {s['global_conditioning_index']:.3f}")
rect = ws.rectangle
print(f"largest rectangle {rect.size[0]:.2f} × {rect.size[1]:.2f} m ({rect.axes}) "
      f"centred at {np.round(rect.centre, 3)}")

# %%
# Why the other points are out
# ----------------------------
# ``reason_counts`` counts the first broken rule per point: a chain falling short, a joint at
# a limit, a singularity margin.
for reason, count in sorted(s["reason_counts"].items(), key=lambda kv: -kv[1])[:6]:
    print(f"  {count:6d}  {reason}")

# %%
# The map
# -------
# Left: the local conditioning index of each reachable point, with the largest rectangle.
# Right: the first rule broken, as a code (``summary['reason_codes']`` names them).
y, z = ws.grid.coordinates(0), ws.grid.coordinates(1)
extent = (y[0], y[-1], z[0], z[-1])
reachable = ws.image("reachable").astype(bool)
conditioning = np.where(reachable, ws.image("conditioning"), np.nan)
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9.5, 4.2))
im = ax1.imshow(conditioning.T, origin="lower", extent=extent, cmap="viridis")
ax1.add_patch(plt.Rectangle((rect.low[1], rect.low[2]), rect.size[0], rect.size[1],
                            fill=False, color="r"))
ax1.set_xlim(-0.4, 0.4)
ax1.set_ylim(-0.15, 0.35)
ax1.set_xlabel("y [m]")
ax1.set_ylabel("z [m]")
ax1.set_title("conditioning (reachable)")
fig.colorbar(im, ax=ax1, shrink=0.8)
ax2.imshow(ws.image("reason").T, origin="lower", extent=extent, cmap="tab20",
           interpolation="nearest")
ax2.set_xlabel("y [m]")
ax2.set_title("first rule broken (code)")
fig.tight_layout()
plt.show()

# %%
# Other tool orientations
# -----------------------
# The reachable area depends on the tool orientation, given as ZYZ angles (ψ, θ, φ) in
# rad. :func:`pollard_pin.largest_panel` gives only the largest panel of a plane.
for deg in ((0, 0, 0), (20, 0, 0), (0, 0, 20), (90, 20, -90), (90, 40, -90)):
    opts = pp.WorkspaceOptions(orientation=tuple(np.radians(deg)), resolution=0.01)
    panel = pp.largest_panel(robot, "x=0.55", opts)
    size = "none" if panel is None else f"{panel.size[0]:.2f} × {panel.size[1]:.2f} m"
    print(f"(ψ, θ, φ) = {deg} deg: largest panel {size}")

# %%
# A volume
# --------
# ``volume=True`` maps a box (streamed in chunks); a coarse 3 cm grid here.
vol = pp.map_workspace(robot, None, pp.WorkspaceOptions(volume=True, resolution=0.03))
print(f"reachable volume {vol.summary['volume'] * 1e3:.1f} L, box "
      f"{vol.summary['bounding_box']}")
