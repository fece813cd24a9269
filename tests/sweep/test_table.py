"""The sweep's table (sweep/table.py): the CSV read back with the csv module gives every value
exactly (floats round-trip, lists as JSON, empty for None), and the summary counts and names
what the rows hold."""
import csv
import json

from pollard_pin.names import ACTUATED
from pollard_pin.sweep import summary, write_sweep_table


def test_csv_cells_round_trip(tmp_path):
    rows = [{"variant": "a", "x": 0.1 + 0.2, "ok": True, "com": [0.045, 0.0, 0.0], "n": None},
            {"variant": "b, with a comma", "x": 1e-300, "ok": False, "com": None, "n": 3}]
    path = tmp_path / "t.csv"
    write_sweep_table(rows, path, ["variant", "x", "ok", "com", "n"])
    got = list(csv.DictReader(path.open(newline="")))
    assert [r["variant"] for r in got] == ["a", "b, with a comma"]
    assert [float(r["x"]) for r in got] == [0.1 + 0.2, 1e-300]  # exact
    assert [r["ok"] for r in got] == ["true", "false"]
    assert json.loads(got[0]["com"]) == [0.045, 0.0, 0.0] and got[1]["com"] == ""
    assert [r["n"] for r in got] == ["", "3"]


def test_summary_counts_and_names_the_worst(pool_rows):
    text = summary(pool_rows).splitlines()
    feasible = [r for r in pool_rows if r["feasible"]]
    assert text[0] == (f"{len(pool_rows)} variants: {len(feasible)} feasible, "
                       f"{len(pool_rows) - len(feasible)} infeasible")
    r = feasible[0]
    worst = max(ACTUATED, key=lambda a: r[f"peak_tau_{a}"])
    line = next(t for t in text if t.startswith(r["variant"]))
    assert f"{r[f'peak_tau_{worst}']:.4g}" in line and worst in line
    bad = next(r for r in pool_rows if not r["feasible"] and r["failure_sample"] is not None)
    line = next(t for t in text if t.startswith(bad["variant"]))
    assert f"INFEASIBLE: {bad['failure_kind']} (sample {bad['failure_sample']}" in line
    assert summary(pool_rows, max_rows=2).splitlines()[-1] == \
        f"… {len(pool_rows) - 2} more in the CSV"
