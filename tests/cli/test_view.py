"""``pollard-pin view`` (cli/view.py): without --html it serves the static page's scene live
until Ctrl-C; --html - writes the page to standard output; a bad frame rate is refused. (The
page's contents: tests/viz/test_viewer.py.)"""
import re
import signal
import subprocess
import sys
import time
import urllib.error
import urllib.request

import pytest
from browser import capture_meshcat, find_chromium
from cli_run import ctrl_c_as_at_a_terminal, run_cli

import pollard_pin as pp
from pollard_pin.cli import main
from pollard_pin.run import run_pipeline
from pollard_pin.viz import meshcat_page, viewer

SAMPLES = 401  # thesis curve, 20 s: dense enough for the IK's branch check, quick to solve


@pytest.fixture(scope="module")
def ik(robot):
    return run_pipeline(robot, pp.thesis_trajectory(samples=SAMPLES), dynamics=False).ik


def _without_uuids(x):
    """MeshCat gives every geometry, material and object a fresh random UUID."""
    if isinstance(x, dict):
        return {k: _without_uuids(v) for k, v in x.items() if k not in ("uuid", "geometry",
                                                                        "material")}
    if isinstance(x, list):
        return [_without_uuids(v) for v in x]
    return x


def test_view_rejects_bad_fps(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["view", "--fps", "0", "--html", "x.html"])
    assert exc.value.code == 2


def _read_until(proc, pattern, timeout):
    deadline = time.monotonic() + timeout
    lines = []
    while time.monotonic() < deadline:
        line = proc.stdout.readline()
        if not line:
            if proc.poll() is not None:
                break
            continue
        lines.append(line)
        m = re.search(pattern, line)
        if m:
            return m, lines
    raise AssertionError(f"no {pattern!r} in output: {lines}; stderr: "
                         f"{proc.stderr.read() if proc.poll() is not None else ''}")


def test_live_server_serves_the_same_scene(ik, robot, tmp_path):
    """``view`` without --html: MeshCat's server on localhost holds exactly the scene of the
    static page (which is therefore MeshCat's static export of it), a browser connected to
    it gets the animation, and Ctrl-C stops everything."""
    import zmq

    proc = subprocess.Popen([sys.executable, "-m", "pollard_pin.cli", "view", "--samples",
                             str(SAMPLES), "--quiet"], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True,
                            preexec_fn=ctrl_c_as_at_a_terminal)
    try:
        m, seen = _read_until(proc, r"MeshCat viewer: (http://127\.0\.0\.1:\d+/static/)", 60)
        web_url = m.group(1)
        m, more = _read_until(proc, r"zmq (tcp://127\.0\.0\.1:\d+)", 5)
        seen += more
        ctx = zmq.Context.instance()
        sock = ctx.socket(zmq.REQ)
        sock.setsockopt(zmq.RCVTIMEO, 20000)
        sock.connect(m.group(1))
        sock.send(b"get_scene")
        server_html = sock.recv().decode()
        sock.close(0)
        live = meshcat_page.page_commands(server_html)
        static = meshcat_page.page_commands(viewer.static_html(robot, ik))
        assert len(live) == len(static) > 30
        assert _without_uuids(live) == _without_uuids(static)
        with urllib.request.urlopen(web_url, timeout=10) as r:
            assert b"MeshCat" in r.read()
        if find_chromium():
            facts = capture_meshcat(web_url, tmp_path / "live.png")
            assert facts["duration"] == pytest.approx(20.0)
            assert facts["actions"] == len(viewer.viewer_geometry(robot).geometryObjects)
        proc.send_signal(signal.SIGINT)
        assert proc.wait(20) == 0  # a hang guard, not a timing: it stops in ~0.2 s
        rest = proc.stdout.read()
        assert "stopping the MeshCat server" in rest
        said = "".join(seen) + rest + proc.stderr.read()
        assert said.count(web_url.rstrip("/").rsplit("/", 1)[0]) == 1, said  # the URL, once
        with pytest.raises((urllib.error.URLError, ConnectionError)):
            urllib.request.urlopen(web_url, timeout=5)
    finally:
        if proc.poll() is None:  # a failed assertion: SIGTERM lets view stop its server
            proc.terminate()
            try:
                proc.wait(20)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait()


def test_html_to_standard_output_is_the_page(capsys):
    code, out, err = run_cli(["view", "--samples", "51", "--quiet", "--html", "-"], capsys)
    assert code == 0, err
    assert out.startswith("<!DOCTYPE html>") and out.rstrip().endswith("</html>")
    assert "wrote" not in err
    cmds = meshcat_page.page_commands(out)
    assert any(c["type"] == "set_animation" for c in cmds)
