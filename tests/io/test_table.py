"""Result tables (io/table.py): a bad file is one error naming the path and what is wrong;
a broken or unwritable sidecar is named; written tables read back bit for bit."""
import numpy as np
import pytest

from pollard_pin.io.table import column_unit, read_result, units_path, write_table
from pollard_pin.paths.curves import ThesisTrajectory
from pollard_pin.run import stream_run


@pytest.mark.parametrize("name, content, says", [
    ("missing.csv", None, "no such result file"),
    ("folder.csv", "DIR", "is a folder"),
    ("garbage.parquet", b"not parquet at all", "not a readable parquet result table"),
    ("empty.csv", b"", "not a readable csv result table"),
    ("latin1.csv", "t,x\n0,\xe9\n".encode("latin-1"), "not UTF-8 text (byte 6"),
    ("text.csv", b"t,x\n0,abc\n", "not a readable csv result table"),
    ("ragged.csv", b"t,x\n0,1,2,3\n", "not a readable csv result table"),
    ("ab.csv", b"a,b\n", "column 'a' is not one pollard-pin writes, and no sidecar"),
    ("ab_rows.csv", b"t,b\n0,1\n", "column 'b' is not one pollard-pin writes"),
    ("header.csv", b"t,theta21\n", "no rows"),
    ("twice.csv", b"t,t\n0,1\n", "duplicate column 't'"),
    ("text.parquet", "TEXT", "not a readable parquet result table"),
])
def test_read_result_of_a_bad_file_is_one_error(tmp_path, name, content, says):
    from pollard_pin.io.table import ResultFileError

    path = tmp_path / name
    if content == "DIR":
        path.mkdir()
    elif content == "TEXT":  # Parquet with a text column
        import pyarrow as pa
        import pyarrow.parquet as pq

        pq.write_table(pa.table({"t": [0.0], "theta21": ["abc"]}), path)
    elif content is not None:
        path.write_bytes(content)
    with pytest.raises(ResultFileError) as info:
        read_result(path)
    assert str(info.value).startswith(f"{path}: ") and says in str(info.value)
    assert "\n" not in str(info.value)


def test_read_result_names_a_broken_sidecar(robot, tmp_path):
    from pollard_pin.io.table import ResultFileError

    path = tmp_path / "r.csv"
    stream_run(robot, ThesisTrajectory(samples=5), path)
    units_path(path).write_text("{broken")
    with pytest.raises(ResultFileError, match=r"r\.units\.json: not a readable units sidecar"):
        read_result(path)


@pytest.mark.parametrize("name", ["r.csv", "r.parquet"])
def test_written_chunks_read_back_bit_for_bit_with_units(tmp_path, name):
    # Floats that a short decimal would round: long mantissas, subnormals, the extremes, −0.
    rng = np.random.default_rng(7)
    odd = np.array([np.nextafter(0.1, 1.0), 5e-324, -2.2250738585072014e-308,
                    1.7976931348623157e308, -0.0, 1 / 3, np.pi * 1e-17, -1e22])
    cols = {"t": np.arange(12.0) * 0.1, "theta21": rng.normal(size=12),
            "tau_theta21": np.concatenate([odd, rng.normal(size=4) * 1e-9])}
    chunks = [{k: v[:5] for k, v in cols.items()}, {k: v[5:] for k, v in cols.items()}]
    assert write_table(tmp_path / name, chunks, {"run": [1, "a"]}) == 12
    back = read_result(tmp_path / name)
    assert list(back.columns) == list(cols) and back.metadata == {"run": [1, "a"]}
    for k, v in cols.items():
        assert back[k].tobytes() == v.tobytes(), k  # the same bits, −0 included
        assert back.units[k] == column_unit(k)


def test_non_finite_metadata_is_one_line_and_nothing_written(tmp_path):
    """Metadata with a NaN or an infinity would make the sidecar (or Parquet's metadata)
    invalid JSON: refused before anything is written, naming the key."""
    from pollard_pin.io.json_text import NonFiniteError

    for name in ("t.csv", "t.parquet"):
        with pytest.raises(NonFiniteError, match=r"metadata: wrench\[3\] = inf"):
            write_table(tmp_path / name, {"t": np.zeros(2)},
                        {"wrench": [0.0, 0.0, 0.0, float("inf")]})
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("path", [3, None, ""])
def test_read_result_refuses_what_names_no_file(path):
    from pollard_pin.io.table import ResultFileError

    with pytest.raises(ResultFileError, match="^path = .*: (expected a file path|an empty path)"):
        read_result(path)


@pytest.mark.parametrize("name", ["run.png", "run.JSON", "r.toml"])
def test_a_table_under_another_formats_name_is_refused(tmp_path, name):
    """``run --out run.png`` wrote CSV text into a file every viewer takes for an image; now
    one line, nothing written. A .csv, .parquet or any other name is written as before."""
    from pollard_pin.io.atomic import OutputError
    from pollard_pin.io.table import table_files

    with pytest.raises(OutputError, match="name for a table: name it .csv or .parquet"):
        table_files(tmp_path / name)
    with pytest.raises(OutputError):
        write_table(tmp_path / name, {"t": np.arange(3.0)})
    assert list(tmp_path.iterdir()) == []
    write_table(tmp_path / "r.txt", {"t": np.arange(3.0)})  # not another format's: CSV
    assert (tmp_path / "r.txt").read_text().startswith("t\n")
