"""Where a sweep runs (sweep/backends.py): serially, on a forked or spawned process pool, on a
Dask cluster, the rows are the same and in input order."""
import pollard_pin as pp
from pollard_pin.sweep import run_sweep, write_sweep_table


def test_serial_equals_pool(sweep, pool_rows):
    assert run_sweep(sweep, workers=1) == pool_rows


def test_spawned_pool_equals_pool(sweep, pool_rows):
    # the start method used in a threaded parent: workers import everything afresh
    assert run_sweep(sweep, workers=2, mp_context="spawn") == pool_rows


def test_dask_local_cluster_gives_the_pool_table(sweep, pool_rows, tmp_path):
    from distributed import Client, LocalCluster

    # processes=True: real worker processes (spawned by dask's nannies), as on a cluster.
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster:
        rows = run_sweep(sweep, dask=cluster.scheduler_address)  # by address, as the CLI does
        with Client(cluster) as client:
            rows_client = run_sweep(sweep, dask=client)
    assert rows == pool_rows
    assert rows_client == pool_rows
    write_sweep_table(pool_rows, tmp_path / "pool.csv", sweep.columns)
    write_sweep_table(rows, tmp_path / "dask.csv", sweep.columns)
    assert (tmp_path / "pool.csv").read_bytes() == (tmp_path / "dask.csv").read_bytes()


def test_run_sweep_refuses_what_is_not_a_sweep():
    import pytest

    from pollard_pin.errors import InputError

    with pytest.raises(InputError, match=r"^sweep = 'x': expected a Sweep \(pollard_pin"):
        run_sweep("x")
    with pytest.raises(InputError, match="^progress = 'x': expected a function or None"):
        run_sweep(pp.make_sweep(grid={"bodies.gun.mass": [0.05]}, samples=11), progress="x")
