"""Outputs written all or none (pollard_pin.io.atomic): the transaction, the up-front checks,
symbolic links, special files and write errors."""
from __future__ import annotations

import errno
import os
import re
from pathlib import Path

import pytest

from pollard_pin.errors import PollardError
from pollard_pin.io.atomic import (
    OutputError,
    all_or_nothing,
    atomic_open,
    check_destination,
    check_name,
    check_not_inputs,
    check_outputs,
    make_folder,
    remove_stale,
)
from pollard_pin.io.table import read_result, table_files, write_table


def _listing(root: Path) -> dict:
    return {str(p.relative_to(root)): (p.read_bytes() if p.is_file() else None)
            for p in sorted(root.rglob("*"))}


def test_a_block_renames_every_file_at_its_end_and_none_before(tmp_path):
    (tmp_path / "a.txt").write_text("old a")
    with all_or_nothing():
        for name in ("a.txt", "b.txt"):
            with atomic_open(tmp_path / name) as f:
                f.write(f"new {name}")
        # staged, not yet in place: the old a, no b
        assert (tmp_path / "a.txt").read_text() == "old a"
        assert not (tmp_path / "b.txt").exists()
    assert (tmp_path / "a.txt").read_text() == "new a.txt"
    assert (tmp_path / "b.txt").read_text() == "new b.txt"
    assert sorted(os.listdir(tmp_path)) == ["a.txt", "b.txt"]  # no temporary file left


def test_a_failure_anywhere_in_the_block_leaves_every_output_as_it_was(tmp_path):
    (tmp_path / "a.txt").write_text("old a")
    (tmp_path / "stale.csv").write_text("stale")
    before = _listing(tmp_path)
    with pytest.raises(RuntimeError, match="third"), all_or_nothing():
        with atomic_open(tmp_path / "a.txt") as f:
            f.write("new a")
        make_folder(tmp_path / "new" / "deep")
        with atomic_open(tmp_path / "new" / "deep" / "b.txt") as f:
            f.write("new b")
        remove_stale(tmp_path / "stale.csv")
        raise RuntimeError("the third output failed")
    assert _listing(tmp_path) == before  # the folders made are gone too, the stale file stays


def test_nested_blocks_join_the_outer_one(tmp_path):
    with pytest.raises(RuntimeError), all_or_nothing():
        with all_or_nothing(), atomic_open(tmp_path / "a.txt") as f:
            f.write("a")
        assert not (tmp_path / "a.txt").exists()  # the inner block did not commit
        raise RuntimeError
    assert os.listdir(tmp_path) == []


def test_a_table_and_its_sidecar_appear_together(tmp_path):
    # the sidecar fails (a folder of its name): the table must not appear either; the old
    # code renamed the table first
    (tmp_path / "t.units.json").mkdir()
    with pytest.raises(OutputError, match="is a folder"):
        write_table(tmp_path / "t.csv", {"t": [0.0, 1.0]})
    assert sorted(os.listdir(tmp_path)) == ["t.units.json"]
    assert table_files(tmp_path / "t.csv") == (tmp_path / "t.csv", tmp_path / "t.units.json")
    assert table_files(tmp_path / "t.parquet") == (tmp_path / "t.parquet",)
    assert table_files("-") == ("-",)


def test_one_file_written_twice_in_a_block_is_refused(tmp_path):
    with pytest.raises(OutputError, match="written twice"), all_or_nothing():
        for _ in range(2):
            with atomic_open(tmp_path / "a.txt") as f:
                f.write("x")
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("name, meant", [("w/../w2", "w2"), ("a/b/../../c.csv", "c.csv"),
                                         ("e/a/../x", "e/x"), ("e/a/../../../z", "e/../../z")])
@pytest.mark.parametrize("folder", [False, True])
def test_dot_dot_out_of_a_missing_folder_is_refused_and_makes_nothing(tmp_path, monkeypatch,
                                                                      name, meant, folder):
    """'w/../w2' resolves only once w is made, and w was left behind, empty: refused, the
    path meant named (os.path.normpath of the missing part: no link can lie below it)."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "e").mkdir()
    with pytest.raises(OutputError, match=re.escape(f"which does not exist (it would be made "
                                                    f"only to be left empty): give {meant}")):
        check_destination(name, folder=folder)
    with pytest.raises(OutputError), all_or_nothing():
        make_folder(name)
    assert os.listdir(tmp_path) == ["e"] and not os.listdir(tmp_path / "e")
    # out of a folder that exists, '..' is the system's: made, and gone again on a failure
    with pytest.raises(RuntimeError), all_or_nothing():
        make_folder("e/../w2/deep")
        raise RuntimeError("the work failed")
    assert os.listdir(tmp_path) == ["e"]
    assert make_folder("e/../w2").resolve() == tmp_path / "w2"


def test_check_outputs_refuses_two_outputs_naming_one_file(tmp_path):
    (tmp_path / "real.csv").write_text("x")
    (tmp_path / "link.csv").symlink_to("real.csv")
    os.link(tmp_path / "real.csv", tmp_path / "hard.csv")
    (tmp_path / "sub").mkdir()  # '..' out of a missing folder is refused on its own
    for a, b in [("x.csv", "x.csv"), ("x.csv", "./x.csv"), ("sub/../x.csv", "x.csv"),
                 ("link.csv", "real.csv"), ("hard.csv", "real.csv"), ("-", "-")]:
        with pytest.raises(OutputError, match="named by two outputs"):
            check_outputs(tmp_path / a if a != "-" else a, tmp_path / b if b != "-" else b)
    check_outputs(tmp_path / "x.csv", tmp_path / "y.csv", "-", folders=(tmp_path / "sub",))
    check_outputs(os.devnull, os.devnull)  # a device takes several outputs


@pytest.mark.parametrize("make, says", [
    (lambda p: p.symlink_to("nowhere/x.csv"), "a dangling symbolic link (to nowhere/x.csv)"),
    (lambda p: p.symlink_to(p.name), "a symbolic link loop"),
])
@pytest.mark.parametrize("folder", [False, True])
def test_a_dangling_or_looping_link_is_refused_before_any_work(tmp_path, make, says, folder):
    make(tmp_path / "out")
    with pytest.raises(OutputError, match=re.escape(says)):
        check_destination(tmp_path / "out", folder=folder)
    with pytest.raises(OutputError, match=re.escape("out is " + says)):
        check_destination(tmp_path / "out" / "inside.csv")  # a parent that leads nowhere
    with pytest.raises(OutputError, match=re.escape(says)):
        with atomic_open(tmp_path / "out") as f:
            f.write("x")
    assert os.path.islink(tmp_path / "out")  # the link itself is left alone


@pytest.mark.parametrize("name, says", [
    ("a" * 300 + ".csv", "holds a name of 304 bytes, over the 255 a file system takes"),
    ("é" * 128, "holds a name of 256 bytes"),  # bytes, not characters
    ("/".join(["b" * 200] * 25), "bytes long, over the 4096 a file system takes"),
])
@pytest.mark.parametrize("folder", [False, True])
def test_a_name_too_long_for_the_file_system_is_one_short_line(tmp_path, name, says, folder):
    # os.stat's ENAMETOOLONG came out of Path.exists() as a traceback, in every command
    with pytest.raises(OutputError) as info:
        check_outputs(*([] if folder else [tmp_path / name]),
                      folders=(tmp_path / name,) if folder else ())
    msg = str(info.value)
    assert says in msg and msg.endswith(": give a shorter one") and len(msg) < 160, msg
    assert list(tmp_path.iterdir()) == []
    check_name(tmp_path / ("a" * 255))  # the longest name is taken


def test_a_link_to_a_file_is_written_through_and_stays_a_link(tmp_path):
    (tmp_path / "data").mkdir()
    (tmp_path / "data" / "real.txt").write_text("old")
    (tmp_path / "link.txt").symlink_to("data/real.txt")
    with all_or_nothing(), atomic_open(tmp_path / "link.txt") as f:
        f.write("new")
    assert os.path.islink(tmp_path / "link.txt")  # the old code replaced the link
    assert (tmp_path / "data" / "real.txt").read_text() == "new"
    assert sorted(os.listdir(tmp_path / "data")) == ["real.txt"]


def test_a_full_device_is_one_line_naming_it_and_why():
    if not os.path.exists("/dev/full"):
        pytest.skip("no /dev/full")
    for binary in (False, True):
        with pytest.raises(OutputError, match="^/dev/full: cannot write: no space left on "
                                              "device$"):
            with atomic_open("/dev/full", binary=binary) as f:
                f.write(b"x" * 100 if binary else "x" * 100)


def test_a_rust_os_error_is_named_by_its_reason(tmp_path):
    # polars reports a full disk as OSError("No space left on device (os error 28)")
    with pytest.raises(OutputError, match="a.csv: cannot write: no space left on device"):
        with atomic_open(tmp_path / "a.csv", binary=True):
            raise OSError(f"{os.strerror(errno.ENOSPC)} (os error {errno.ENOSPC})")
    assert os.listdir(tmp_path) == []
    with pytest.raises(BrokenPipeError):  # a closed reader stays a closed pipe
        with atomic_open(tmp_path / "a.csv"):
            raise BrokenPipeError(errno.EPIPE, "Broken pipe")
    assert issubclass(OutputError, PollardError)


def test_a_special_file_is_written_in_place_and_text_files_are_utf8(tmp_path):
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    reader = os.open(fifo, os.O_RDONLY | os.O_NONBLOCK)
    try:
        with all_or_nothing(), atomic_open(fifo) as f:
            f.write("µ θ\n")
        assert os.read(reader, 100) == "µ θ\n".encode()
    finally:
        os.close(reader)
    assert fifo.is_fifo()
    with atomic_open(tmp_path / "u.txt") as f:
        f.write("σ ± µ")
    assert (tmp_path / "u.txt").read_bytes() == "σ ± µ".encode()


def test_remove_stale_removes_files_and_links_only(tmp_path):
    (tmp_path / "old.csv").write_text("x")
    (tmp_path / "old.parquet").mkdir()
    (tmp_path / "link.csv").symlink_to("nowhere")
    remove_stale(tmp_path / "old.csv", tmp_path / "old.parquet", tmp_path / "link.csv",
                 tmp_path / "absent.csv")
    assert os.listdir(tmp_path) == ["old.parquet"]


def test_a_table_read_back_after_the_block(tmp_path):
    with all_or_nothing():
        write_table(tmp_path / "t.csv", {"t": [0.0, 1.0], "x": [0.5, 0.25]}, {"k": "µ"})
    table = read_result(tmp_path / "t.csv")
    assert table["x"].tolist() == [0.5, 0.25] and table.metadata == {"k": "µ"}


def test_an_output_that_is_an_input_is_refused_however_named(tmp_path):
    """The same file by its name, another spelling, a symbolic link or a hard link is one of
    the inputs; another file, standard output and /dev/null are not."""
    mesh = tmp_path / "part" / "film.ply"
    mesh.parent.mkdir()
    mesh.write_bytes(b"mesh bytes")
    (tmp_path / "link.ply").symlink_to(mesh)
    os.link(mesh, tmp_path / "hard.ply")
    inputs = [("the mesh", mesh), ("the job", tmp_path / "absent.toml"), ("none", None)]
    for out, also in [(mesh, ""), (tmp_path / "part" / ".." / "part" / "film.ply", ""),
                      (tmp_path / "link.ply", f", {mesh}"), (tmp_path / "hard.ply", f", {mesh}")]:
        with pytest.raises(OutputError) as exc:
            check_not_inputs([None, out], inputs)
        assert str(exc.value) == (f"{out}: is one of the inputs (the mesh{also}): writing it "
                                  "would destroy it, give another path")
    check_not_inputs([tmp_path / "other.ply", "-", "/dev/null", tmp_path / "absent.toml"],
                     inputs + [("stdin", "-"), ("null", "/dev/null")])
    assert mesh.read_bytes() == b"mesh bytes"
