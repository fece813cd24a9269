"""SIGTERM and Ctrl-C (cli/main.py): ``size`` on a long path with a wait stops promptly with
one line, exit 143 / 130, and writes nothing; an interrupt raised inside a ctypes call's
argument conversion (rtree's queries), which ctypes wraps in ``ctypes.ArgumentError``, is the
same one line."""
import ctypes
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
from motor_model import EXAMPLE, ROOT
from motor_model import cli as _cli

import pollard_pin as pp
from pollard_pin.cli import size as size_cli
from pollard_pin.paths.curves import thesis_curve


def _wait_then_strokes(path, n=40_000, dt=2e-3):
    """A line job's shape: a wait of 47 % of the samples at 2 ms steps, then the thesis curve
    once over from rest to rest."""
    wait = int(n * 0.47)
    moving = n - wait
    T = (moving - 1) * dt
    x = np.linspace(0.0, 1.0, moving)
    u = T * (10 * x**3 - 15 * x**4 + 6 * x**5)
    du, ddu = 30 * x**2 - 60 * x**3 + 30 * x**4, (60 * x - 180 * x**2 + 120 * x**3) / T
    p, d, dd = thesis_curve(u, T)
    zero = np.zeros((wait, 6))
    t = np.concatenate([dt * np.arange(wait), dt * wait + x * T])
    pp.to_csv(pp.Trajectory(t, np.vstack([np.repeat(p[:1], wait, 0), p]),
                            np.vstack([zero, d * du[:, None]]),
                            np.vstack([zero, dd * du[:, None] ** 2 + d * ddu[:, None]])), path)


@pytest.mark.parametrize("signum, code, word", [(signal.SIGTERM, 143, "terminated"),
                                                (signal.SIGINT, 130, "interrupted")])
def test_size_stops_within_a_second_of_a_signal(tmp_path, signum, code, word):
    _wait_then_strokes(tmp_path / "long.csv")  # 40,000 samples: size takes ≈ 8 s here
    out = tmp_path / "out"
    out.mkdir()
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    proc = subprocess.Popen(
        [sys.executable, "-m", "pollard_pin.cli", "size", "--trajectory", str(tmp_path /
         "long.csv"), "--actuators", str(EXAMPLE), "--quiet", "--out", str(out / "r.md"),
         "--retime", str(out / "fast.csv")], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
        env=env, start_new_session=True)  # Ctrl-C goes to the process alone
    time.sleep(2.0)  # past the imports, into the work
    assert proc.poll() is None, proc.communicate()
    sent = time.monotonic()
    proc.send_signal(signum)
    try:
        _, err = proc.communicate(timeout=30)
    finally:
        proc.kill()
    # seen 0.07-0.47 s, depending on where the signal lands; the promise is 1 s
    assert time.monotonic() - sent < 1.0
    assert proc.returncode == code
    assert err.decode().splitlines() == [f"pollard-pin size: {word}, nothing written"]
    assert list(out.iterdir()) == []


def test_an_interrupt_inside_a_ctypes_call_is_one_line(monkeypatch, capsys):
    class Slow:  # a ctypes argument whose conversion is interrupted (as rtree's are)
        @classmethod
        def from_param(cls, value):
            os.kill(os.getpid(), signal.SIGTERM)
            time.sleep(5)  # the handler raises here, within the call
            return ctypes.c_int(value)

    labs = ctypes.CDLL(None).labs
    labs.argtypes = [Slow]

    monkeypatch.setattr(size_cli, "run", lambda args: labs(1))
    previous = signal.signal(signal.SIGTERM, lambda *_: (_ for _ in ()).throw(
        KeyboardInterrupt))
    try:  # what the command sees: ctypes wraps the interrupt
        with pytest.raises(ctypes.ArgumentError):
            labs(1)
    finally:
        signal.signal(signal.SIGTERM, previous)
    code, out, err = _cli(["size", "--actuators", str(EXAMPLE)], capsys)
    assert (code, out, err) == (143, "", "pollard-pin size: terminated, nothing written\n")
