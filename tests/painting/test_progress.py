"""Progress bars over the planner's long loops: shown only when asked and on a terminal."""
import sys

from pollard_pin.painting.progress import bar, showing, ticking


def _on_a_terminal(monkeypatch, capsys):
    capsys.readouterr()
    monkeypatch.setattr(sys.stderr, "isatty", lambda: True, raising=False)


def test_a_bar_shows_only_when_asked_and_on_a_terminal(monkeypatch, capsys):
    assert list(bar(range(3), "film")) == [0, 1, 2]  # not asked: the iterable itself
    with showing(True):  # asked, standard error not a terminal: silent
        assert list(bar(range(3), "film")) == [0, 1, 2]
    assert capsys.readouterr().err == ""
    _on_a_terminal(monkeypatch, capsys)
    with showing(True):
        assert list(bar(range(3), "film")) == [0, 1, 2]
    assert "film" in capsys.readouterr().err
    assert list(bar(range(3), "film")) == [0, 1, 2]  # the block ended: off again
    assert capsys.readouterr().err == ""


def test_a_ticking_bar_counts_each_tick(monkeypatch, capsys):
    with ticking("line speed search", "plan") as tick:
        tick()
    assert capsys.readouterr().err == ""
    _on_a_terminal(monkeypatch, capsys)
    with showing(True), ticking("line speed search", "plan") as tick:
        for _ in range(3):
            tick()
    assert "line speed search" in capsys.readouterr().err
