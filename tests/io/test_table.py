"""Result tables (io/table.py): a bad file is one error naming the path and what is wrong;
a broken or unwritable sidecar is named; written tables read back bit for bit."""
import pytest

from pollard_pin.io.table import read_result, units_path
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
