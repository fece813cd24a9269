"""
Design sweeps, on one machine and on a Dask cluster
===================================================

Evaluate many variants of the robot's parameters along one trajectory: every variant runs
through the inverse kinematics and dynamics, and yields one row (the swept values, whether it
is feasible and, if not, why; peak and RMS torques, peak powers, closure forces, singularity
margins, bearing loads). The command line: ``pollard-pin sweep --grid sweep.toml``.
"""

# %%
# The sweep
# ---------
# :func:`pollard_pin.make_sweep` takes a grid (a cartesian product) and explicit variants.
# Keys are the dotted keys of ``models/pollard.toml`` in its units (m, deg, kg, kg·mm²);
# ``"key[i]"`` is one component of a vector parameter. A coarse thesis path (201 samples)
# keeps this page quick; :func:`pollard_pin.load_grid` reads the same from a TOML file.
import time

import matplotlib.pyplot as plt

import pollard_pin as pp

sweep = pp.make_sweep(
    grid={"chain0.x32": [0.32, 0.33, 0.34], "bodies.gun.mass": [0.035, 0.05]},
    variants=[("long legs", {"leg1.x87": 0.34, "leg2.x87": 0.34}),
              ("short leg 1", {"leg1.x87": 0.31})],
    samples=201)
print(f"{len(sweep.specs())} variants; columns start {sweep.columns[:6]}")

# %%
# On this machine
# ---------------
# :func:`pollard_pin.run_sweep` runs the variants on a local process pool (every core by
# default; ``workers=1`` runs them in this process) and returns the rows in variant order.
start = time.perf_counter()
rows = pp.run_sweep(sweep, workers=2)
print(f"{len(rows)} variants in {time.perf_counter() - start:.1f} s on 2 processes")
for row in rows:
    if row["feasible"]:
        print(f"  {row['variant']:28s} peak |τ| theta21_1 {row['peak_tau_theta21_1']:.3f} N·m, "
              f"leg-1 force {row['peak_force_leg1']:.2f} N")
    else:
        print(f"  {row['variant']:28s} infeasible: {row['failure_kind']} at "
              f"t = {row['failure_time']} s")

# %%
# How the base link length and the gun's mass load the motors
# -----------------------------------------------------------
fig, ax = plt.subplots(figsize=(6.5, 3.6))
for mass in (0.035, 0.05):
    sel = [r for r in rows if r.get("bodies.gun.mass") == mass and r["feasible"]]
    ax.plot([r["chain0.x32"] for r in sel], [r["peak_tau_theta21"] for r in sel], "o-",
            label=f"gun {mass * 1e3:.0f} g")
ax.set_xlabel("chain0.x32 [m]")
ax.set_ylabel("peak |τ| theta21 [N·m]")
ax.legend()
fig.tight_layout()
plt.show()

# %%
# On a Dask cluster
# -----------------
# The same sweep runs on a Dask cluster: ``dask=`` takes a scheduler address
# (``"tcp://scheduler:8786"``, whose workers have pollard-pin installed) or a
# ``distributed.Client``. A local cluster in this process stands in for one here (its
# workers as threads, so that this script needs no ``if __name__ == "__main__":`` guard).
# Dask is an optional extra: ``pip install "pollard-pin[cluster]"``.
try:
    from distributed import Client, LocalCluster
except ImportError:
    Client = None
    print("dask.distributed is not installed: skipping the cluster run "
          "(pip install 'pollard-pin[cluster]')")

if Client is not None:
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=False,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        start = time.perf_counter()
        dask_rows = pp.run_sweep(sweep, dask=client)
        print(f"{len(dask_rows)} variants in {time.perf_counter() - start:.1f} s on Dask")
    same = all(a == b for a, b in zip(rows, dask_rows))
    print("the same rows as the local pool:", same)
