"""
The 3D viewer: a static page
============================

:func:`pollard_pin.write_html` writes the robot moving along a trajectory as one
self-contained MeshCat page (about 3 MB): any browser opens it from disk, offline. Open the
controls, then *Animations → default* to play, pause or drag *time*.

The command line does the same (``pollard-pin view --html pollard.html``), and without
``--html`` serves the scene live on localhost; ``view --paint DIR`` adds a paint job's film
and ``view --workspace DIR`` a workspace map's reachable points.
"""

# %%
# Solve the kinematics only
# -------------------------
# The viewer needs joint angles, not torques: ``dynamics=False`` skips the inverse dynamics.
from pathlib import Path

import matplotlib.pyplot as plt

import pollard_pin as pp

robot = pp.load()
traj = pp.thesis_trajectory(duration=20.0, samples=201)
ik = pp.run_pipeline(robot, traj, dynamics=False).ik

# %%
# Write the page
# --------------
# ``frames=True`` adds the tool and platform frames as triads; ``fps`` sets the key frames
# per second of trajectory time (25 by default). The page is written next to this
# tutorial's output, so the site can link it.
page = pp.write_html(Path("pollard_viewer.html"), robot, ik, frames=True)
print(f"wrote {page} ({page.stat().st_size / 1e6:.1f} MB)")

# %%
# .. raw:: html
#
#     <p><a href="pollard_viewer.html">Open the viewer page</a> (MeshCat, about 3 MB).</p>
#
# What the page animates
# ----------------------
# The tool tip's path and the key joint angles the page plays back, from the same solution.
fig = plt.figure(figsize=(9, 3.8))
ax = fig.add_subplot(1, 2, 1, projection="3d")
ax.plot(*ik.poses[:, :3].T)
ax.set_xlabel("x [m]")
ax.set_ylabel("y [m]")
ax.set_zlabel("z [m]")
ax.set_title("tool tip")
ax2 = fig.add_subplot(1, 2, 2)
for name in robot.actuated[:3]:
    ax2.plot(ik.t, ik.q[:, robot.joint_names.index(name)], label=name)
ax2.set_xlabel("t [s]")
ax2.set_ylabel("angle [rad]")
ax2.legend(fontsize=8)
fig.tight_layout()
plt.show()
