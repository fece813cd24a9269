"""Stripe files (io/stripes.py): the example reads back as written; every file or value a
calibration cannot use is one StripeError line naming the stripe and what to measure."""
import os
from pathlib import Path

import numpy as np
import pytest

from pollard_pin.io.stripes import Stripe, StripeError, StripeSet, read_stripes

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "stripes" / "stripes.toml"
TOP = 'solids = 0.45\n[[stripe]]\nfile = "s.csv"\nstandoff = 0.2\nspeed = 0.5\n' \
      'flow = 2e-6\ndirection = "across"\n'


def _csv(x, t) -> str:
    return "position,thickness\n" + "".join(f"{float(a)!r},{float(b)!r}\n" for a, b in zip(x, t))


def _good():
    x = np.linspace(-0.1, 0.1, 101)
    return x, 2e-5 * np.exp(-0.5 * (x / 0.02) ** 2)


def test_the_example_reads_back():
    s = read_stripes(EXAMPLE)
    assert len(s.stripes) == 8 and s.solids == 0.45 and s.standoff == 0.2
    assert {st.direction for st in s.stripes} == {"across", "along"}
    assert {st.standoff for st in s.stripes} == {0.15, 0.25}
    first = s.stripes[0]
    assert len(first.position) == 301 and first.position[0] == -0.15
    assert np.all(np.diff(first.position) > 0) and not first.position.flags.writeable
    assert len(s.files) == 8 and all(f.is_file() for f in s.files)


def test_a_stripe_scanned_the_other_way_is_stored_rising():
    x, t = _good()
    s = Stripe(x[::-1], t[::-1], 0.2, 0.5, 2e-6, "along")
    assert np.array_equal(s.position, x) and np.array_equal(s.thickness, t)


X, T = _good()
BAD_CSV = [
    ("non-monotone", _csv(np.r_[X[:50], X[51], X[50], X[52:]], T), "positions must rise"),
    ("repeated", _csv(np.r_[X[:50], X[50], X[50], X[52:]], T), "line 53: position 0 m after 0 m"),
    ("nan", _csv(X, np.r_[T[:10], np.nan, T[11:]]), "line 12: thickness is nan"),
    ("text", _csv(X, T).replace(repr(float(T[5])), "abc"),
     "line 7: thickness 'abc' is not a number"),
    ("huge", _csv(X, np.r_[T[:10], 1e300, T[11:]]), "over 1 mm of dry film: thickness in µm?"),
    ("mm", _csv(X * 1e3, T), "a pattern wider than 1 m: positions in mm? give metres"),
    ("microns", _csv(X, T * 1e6), "thickness in µm? give metres"),
    ("millimetres", _csv(X, T * 1e3), "up to 0.02 m, over 1 mm of dry film: thickness in mm?"),
    ("columns", "x,y\n0,1\n", "columns 'x,y': expected 'position,thickness'"),
    ("column twice", _csv(X, T).replace("thickness\n", "thickness,thickness\n", 1),
     "columns 'position,thickness,thickness': expected 'position,thickness' once each"),
    ("few", _csv(X[:5], T[:5]), "5 points: measure at least 10"),
    ("one", _csv(X[:1], T[:1]), "s.csv: 1 point: measure at least 10"),
    ("ragged", _csv(X, T) + "0.2\n", "1 cells, expected 2"),
    ("latin1", "position,thickness\n0,\xe9\n", "not UTF-8 text (another format?)"),
    ("empty", "", "empty: a stripe is a CSV"),
    ("long cell", _csv(X, T).replace(repr(float(T[5])), "1" * 200_000),
     "line 7: not CSV (field larger than field limit (131072))"),
    ("semicolons", _csv(X, T).replace(",", ";"), "line 1: cells separated by ';': write a comma"),
    ("tabs", _csv(X, T).replace(",", "\t"), "line 1: cells separated by '\\t': write a comma"),
]


@pytest.mark.parametrize("name, content, says", BAD_CSV, ids=[b[0] for b in BAD_CSV])
def test_a_bad_stripe_file_is_one_line(tmp_path, name, content, says):
    (tmp_path / "s.csv").write_bytes(content.encode("latin-1" if name == "latin1" else "utf-8"))
    (tmp_path / "stripes.toml").write_text(TOP)
    with pytest.raises(StripeError) as info:
        read_stripes(tmp_path / "stripes.toml")
    text = str(info.value)
    assert says in text and "\n" not in text and "s.csv" in text, text


BAD_TOML = [
    ("unknown", TOP + "colour = 1\n", "stripe 1: unknown key 'colour'"),
    ("unknown top", "solid = 0.4\n" + TOP, "unknown key 'solid' (did you mean 'solids'?)"),
    ("no solids", TOP.replace("solids = 0.45\n", ""), "'solids' is missing"),
    ("percent", TOP.replace("0.45", "45"), "solids = 45: must be the dry share"),
    ("missing key", TOP.replace("speed = 0.5\n", ""), "'speed' is missing"),
    ("direction", TOP.replace('"across"', '"acros"'), "(did you mean 'across'?)"),
    ("standoff mm", TOP.replace("standoff = 0.2", "standoff = 200"), "in mm? give metres"),
    # a nozzle on the panel: the fit divided by the standoff's square (a ZeroDivisionError)
    ("standoff zero", TOP.replace("standoff = 0.2", "standoff = 1e-300"),
     "stripe 1 (s.csv): standoff = 1e-300: under 0.01 m: no spray gun paints that close"),
    ("standoff 5 mm", TOP.replace("standoff = 0.2", "standoff = 0.005"), "under 0.01 m"),
    ("speed", TOP.replace("speed = 0.5", "speed = 500"), "in mm/s? give m/s"),
    ("flow", TOP.replace("flow = 2e-6", "flow = 120"), "in ml/min or l/min? give m³/s"),
    ("negative", TOP.replace("speed = 0.5", "speed = -0.5"), "must be a finite number > 0"),
    ("no stripes", "solids = 0.4\n", "no stripes"),
    ("missing file", TOP.replace("s.csv", "none.csv"), "none.csv' does not exist"),
    ("not toml", "solids = \n", "is not valid TOML"),
    ("solids per stripe", TOP + "solids = 0.5\n",
     "stripe 1: solids is the paint's, given once at the top"),
    ("twice", TOP + TOP.split("\n", 1)[1].replace('"s.csv"', '"./s.csv"'),
     "stripe 2: file './s.csv' again (stripe 1 has it)"),
]


@pytest.mark.parametrize("name, text, says", BAD_TOML, ids=[b[0] for b in BAD_TOML])
def test_a_bad_stripes_toml_is_one_line(tmp_path, name, text, says):
    x, t = _good()
    (tmp_path / "s.csv").write_text(_csv(x, t))
    (tmp_path / "stripes.toml").write_text(text)
    with pytest.raises(StripeError) as info:
        read_stripes(tmp_path / "stripes.toml")
    assert says in str(info.value) and "\n" not in str(info.value), str(info.value)


def test_a_fifo_is_refused_not_waited_for(tmp_path):
    os.mkfifo(tmp_path / "s.csv")
    (tmp_path / "stripes.toml").write_text(TOP)
    with pytest.raises(StripeError, match=r"not a regular file \(a FIFO\)"):
        read_stripes(tmp_path / "stripes.toml")


def test_a_python_built_set_is_checked_the_same():
    x, t = _good()
    good = Stripe(x, t, 0.2, 0.5, 2e-6, "across")
    with pytest.raises(StripeError, match="solids = 1.5"):
        StripeSet((good,), 1.5)
    with pytest.raises(StripeError, match="no stripes"):
        StripeSet((), 0.4)
    with pytest.raises(StripeError, match="point 3: thickness is inf"):
        Stripe(x, np.r_[t[:2], np.inf, t[3:]], 0.2, 0.5, 2e-6, "across")
    with pytest.raises(StripeError, match="expected two 1-D columns"):
        Stripe(x, t[:-1], 0.2, 0.5, 2e-6, "across")
    assert StripeSet((good,), 1, 0.25).standoff == 0.25
    assert len(StripeSet((good,) * 64, 0.4).stripes) == 64
    with pytest.raises(StripeError, match="65 stripes: at most 64"):
        StripeSet((good,) * 65, 0.4)


def test_the_formats_page_names_every_key():
    from pollard_pin.io.stripes import STRIPE_KEYS, TOP_KEYS

    text = (EXAMPLE.parents[2] / "docs" / "formats.md").read_text(encoding="utf-8")
    section = text.split("### Measured stripes", 1)[1].split("\n## ", 1)[0]
    top, stripe = section.split("`[[stripe]]`:", 1)
    assert all(f"| `{k}`" in top for k in TOP_KEYS), TOP_KEYS
    assert all(f"| `{k}`" in stripe for k in STRIPE_KEYS), STRIPE_KEYS


def test_a_large_file_is_refused_unread_in_one_line(tmp_path):
    (tmp_path / "stripes.toml").write_text(TOP)
    with open(tmp_path / "s.csv", "wb") as f:  # sparse: nothing to write
        f.truncate((16 << 20) + 1)
    with pytest.raises(StripeError) as info:
        read_stripes(tmp_path / "stripes.toml")
    assert str(info.value) == ("s.csv: over 16 MiB: a profile of 100,000 points is ~3 MB; one "
                               "scan per file")


def test_what_a_spreadsheet_writes_reads_the_same(tmp_path):
    x, t = _good()
    plain = _csv(x, t)
    rows = [r.split(",") for r in plain.splitlines()]
    quoted = "\r\n".join(f'"{b}","{a}"' for a, b in rows) + "\r\n"  # CRLF, quoted, swapped
    extra = "".join(f"{i},{r},ok\n" for i, r in enumerate(plain.splitlines()))  # ignored
    extra = "point,position,thickness,flag" + extra.split("position,thickness,ok", 1)[1]
    for i, text in enumerate([plain, "\ufeff" + quoted, "# scan 3\n\n" + plain, extra]):
        folder = tmp_path / str(i)
        folder.mkdir()
        (folder / "s.csv").write_bytes(text.encode("utf-8"))
        (folder / "stripes.toml").write_text(TOP)
        got = read_stripes(folder / "stripes.toml").stripes[0]
        assert np.array_equal(got.position, x) and np.array_equal(got.thickness, t), i


def test_a_column_of_other_things_than_real_numbers_is_one_line():
    x, t = _good()
    for bad, says in ((x.astype(str), "position = "), (x + 0j, "position = "),
                      (["a"] * len(x), "position = ")):
        with pytest.raises(StripeError, match=f"^<python>: {says}.*: expected an array of "
                                              "real numbers"):
            Stripe(bad, t, 0.2, 0.5, 2e-6, "across")
    # numpy's scalars are numbers: a value read from an array is taken
    s = Stripe(x, t, np.float32(0.2), np.int64(1), np.float64(2e-6), "across")
    assert (s.standoff, s.speed) == (pytest.approx(0.2), 1.0)
    assert StripeSet((s,), np.float64(0.45)).solids == 0.45
    with pytest.raises(StripeError, match="speed = np.True_: must be a number"):
        Stripe(x, t, 0.2, np.bool_(True), 2e-6, "across")
