"""What every command shares (cli/common.py): argument types that reject what the API would,
one-line parser errors, negative numbers as values, --set naming its flag, notes said once."""
import argparse
import math
import types

import pytest

from pollard_pin.cli import common as C
from pollard_pin.errors import InputError
from pollard_pin.model.params import ParameterError


@pytest.mark.parametrize("parse, text, value", [
    (C.number, "-1e-3", -1e-3), (C.positive, "2.5", 2.5), (C.nonnegative, "0", 0.0),
    (C.fraction, "1", 1.0), (C.numbers, "0.092,-1e-3", (0.092, -1e-3)),
    (C.count(2), "2", 2), (C.count(1, 3), "3", 3), (C.name, "a", "a"),
])
def test_types_accept(parse, text, value):
    assert parse(text) == value


@pytest.mark.parametrize("parse, text, says", [
    (C.number, "abc", "not a number: 'abc'"), (C.number, "nan", "finite"),
    (C.number, "-inf", "finite"), (C.positive, "0", "must be > 0, got 0"),
    (C.nonnegative, "-1e-9", "must be >= 0, got -1e-9"), (C.fraction, "1.5", "at most 1"),
    (C.numbers, "0.1,,0.2", "not a number: ''"), (C.numbers, "0.1,inf", "finite"),
    (C.count(2), "1", "must be >= 2, got 1"), (C.count(1, 3), "4", "between 1 and 3"),
    (C.count(1), "2.0", "not an integer: '2.0'"), (C.name, "", "an empty name"),
])
def test_types_reject_in_one_line(parse, text, says):
    with pytest.raises(argparse.ArgumentTypeError) as info:
        parse(text)
    assert says in str(info.value) and "\n" not in str(info.value)


@pytest.mark.parametrize("text", ["tcp://127.0.0.1:8786", " localhost:8786 ", "tls://h:1",
                                  "tcp://[::1]:8786", "inproc://x"])
def test_a_scheduler_address_dask_takes_is_taken(text):
    pytest.importorskip("distributed")
    assert C.scheduler_address(text) == text.strip()


@pytest.mark.parametrize("text, says", [
    ("tcp://[::1", "'tcp://[::1' (invalid address '[::1'; maybe: ipv6 needs brackets"),
    ("localhost", "'localhost' (missing port number in address 'localhost')"),
    ("tcp://h:port", "'tcp://h:port' (invalid literal for int()"),
    ("tcp://127.0.0.1:99999", "(port 99999 is not in 1..65535)"),
    ("tpc://127.0.0.1:8786", "(unknown address scheme 'tpc'"),
])
def test_a_malformed_scheduler_address_is_refused_before_any_work(text, says):
    # the old code took any text: design then screened its first generation (84 s) before
    # the connection said the address was malformed
    pytest.importorskip("distributed")
    with pytest.raises(argparse.ArgumentTypeError) as info:
        C.scheduler_address(text)
    msg = str(info.value)
    assert msg.startswith("not a scheduler address: ") and says in msg, msg
    assert msg.endswith("; e.g. tcp://127.0.0.1:8786") and "\n" not in msg, msg


def test_parser_takes_negative_numbers_as_values_and_errs_in_one_line(capsys):
    p = C.Parser(prog="pollard-pin x")
    p.add_argument("--margin", type=C.fraction)
    p.add_argument("--wn", type=C.nonnegative)
    with pytest.raises(SystemExit) as info:
        p.parse_args(["--wn", "-1e-3"])  # a value, so its own check speaks
    assert info.value.code == 2
    err = capsys.readouterr().err
    assert err == "pollard-pin x: error: argument --wn: must be >= 0, got -1e-3\n"
    assert C.NEGATIVE_NUMBER.match("-inf") and C.NEGATIVE_NUMBER.match("-.5e+3")
    assert not C.NEGATIVE_NUMBER.match("-x") and not C.NEGATIVE_NUMBER.match("--set")
    assert math.isclose(p.parse_args(["--margin", "0.5"]).margin, 0.5)


def test_usage_error_is_an_input_error():
    assert issubclass(C.UsageError, InputError)


def test_set_errors_name_the_flag_and_no_set_is_the_shipped_model():
    args = types.SimpleNamespace(params=None, set=["chain0.x32"])
    with pytest.raises(ParameterError, match=r"^--set: "):
        C.params_of(args)
    assert C.params_of(types.SimpleNamespace(params=None, set=[])) is None
    p = C.params_of(types.SimpleNamespace(params=None, set=["chain0.x32=0.34"]))
    assert p.x32 == 0.34


def test_notes_are_said_once_in_order(capsys):
    import warnings

    args = types.SimpleNamespace(notes=[])
    with C.warnings_as_notes(args):
        warnings.warn("second", stacklevel=1)
        warnings.warn("first", stacklevel=1)
        warnings.warn("second", stacklevel=1)
    C.say_notes(args)
    assert capsys.readouterr().err == "note: second\nnote: first\n" and args.notes == []


# --- an output that is one of the inputs --------------------------------------------------------
def _outputs_over_inputs(tmp):
    """(argv, the input it would overwrite) for each command that reads a shared input."""
    import shutil
    from pathlib import Path

    root = Path(__file__).resolve().parents[2]
    ex = root / "examples"
    traj = tmp / "f8.csv"
    shutil.copy(ex / "figure8.csv", traj)
    shutil.copy(ex / "figure8.units.json", tmp / "f8.units.json")
    grid = tmp / "sweep.toml"
    shutil.copy(ex / "sweep.toml", grid)
    act = tmp / "act.toml"
    shutil.copy(ex / "actuators.toml", act)
    t = ["--trajectory", str(traj)]
    return [
        (["run", *t, "--out", str(traj)], traj),
        (["size", "--actuators", str(act), *t, "--retime", str(traj)], traj),
        (["size", "--actuators", str(act), *t, "--retime", str(tmp / "x.csv"), "--out",
          str(act)], act),
        # the table over the trajectory, its sidecar over the trajectory's (a .json name for
        # the table itself is refused first, as another format's: io/table.py)
        (["simulate", *t, "--out", str(traj)], tmp / "f8.units.json"),
        (["sweep", "--grid", str(grid), "--out", str(grid)], grid),
        (["report", *t, "--no-cross-check", "--out", str(traj)], traj),
    ]


def test_an_output_that_is_an_input_is_refused_and_left_alone(tmp_path, capsys):
    """`size --retime in.csv --trajectory in.csv` wrote the retimed file over the path it
    read; every command's outputs are now checked against its inputs before any work."""
    from cli_run import run_cli

    for argv, victim in _outputs_over_inputs(tmp_path):
        before = victim.read_bytes()
        code, out, err = run_cli(argv, capsys)
        lines = err.strip().splitlines()
        assert code == 2 and len(lines) == 1, (argv, err)
        assert "is one of the inputs" in lines[0] and "destroy" in lines[0], lines[0]
        assert victim.read_bytes() == before, argv


@pytest.fixture(scope="module")
def path_csv(tmp_path_factory):
    """A 401-sample thesis trajectory CSV with its units sidecar."""
    import pollard_pin as pp

    folder = tmp_path_factory.mktemp("gravity")
    pp.to_csv(pp.thesis_trajectory(samples=401), folder / "p.csv")
    return folder / "p.csv"


GRAVITY_COMMANDS = {  # every command that reads a trajectory's gravity_base (its out file)
    "run": ["--out", "r.csv"], "size": ["--actuators", "ACT"], "simulate": ["--out", "s.csv"],
    "stiffness": ["--actuators", "ACT", "--out", "st.csv"], "view": ["--html", "v.html"],
    "plot": ["--out", "p.png"], "report": [],
}


@pytest.mark.parametrize("g, says", [([True, 0, -9.81], "not booleans"),
                                     ([0, 0, -1e308], "component of 1e+308 m/s²")])
@pytest.mark.parametrize("cmd", sorted(GRAVITY_COMMANDS))
def test_a_bad_sidecar_gravity_is_exactly_one_line(path_csv, tmp_path, capsys, cmd, g, says):
    """A sidecar's gravity_base of booleans (read as 1, 0 before) or of 1e308 (refused after a
    numpy overflow warning: three lines) is one line in every command that reads it, exit 2,
    nothing written."""
    import json
    import shutil
    from pathlib import Path

    from cli_run import run_cli

    act = Path(__file__).resolve().parents[2] / "examples" / "actuators.toml"
    path = tmp_path / "p.csv"
    shutil.copy(path_csv, path)
    side = json.loads(path_csv.with_name("p.units.json").read_text())
    side["metadata"]["gravity_base"] = g
    (tmp_path / "p.units.json").write_text(json.dumps(side))
    extra = [str(act) if a == "ACT" else (str(tmp_path / a) if "." in a else a)
             for a in GRAVITY_COMMANDS[cmd]]
    code, _, err = run_cli([cmd, *extra, "--trajectory", path, "--quiet"], capsys)
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1, err
    assert lines[0].startswith(f"pollard-pin {cmd}: error: ") and says in lines[0], lines[0]
    assert "p.units.json: metadata 'gravity_base'" in lines[0]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["p.csv", "p.units.json"]
