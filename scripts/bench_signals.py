"""How fast a command stops on SIGTERM and Ctrl-C (the CLI's promise: within a second, one
line, nothing written): `size` on a 40,000-sample path with a wait, signalled at several
moments of its work. Imported by scripts/benchmark.py; timing lives here, not in the tests."""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pollard_pin as pp

REPO = Path(__file__).resolve().parents[1]


def signal_section(path_of, delays=(1.5, 2.5, 3.5)) -> None:
    """``path_of(n)``: a trajectory of n samples (a wait, then strokes)."""
    print("\nstopping on a signal: `size` on 40,000 samples (a wait, then strokes) [s]")
    with tempfile.TemporaryDirectory() as tmp:
        csv = Path(tmp) / "long.csv"
        pp.to_csv(path_of(40_000), csv)
        env = {**os.environ, "PYTHONPATH": str(REPO)}
        for signum, name in ((signal.SIGTERM, "SIGTERM"), (signal.SIGINT, "SIGINT")):
            for delay in delays:
                proc = subprocess.Popen(
                    [sys.executable, "-m", "pollard_pin.cli", "size", "--trajectory", str(csv),
                     "--actuators", str(REPO / "examples/actuators.toml"), "--quiet",
                     "--retime", str(Path(tmp) / "fast.csv")],
                    stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=env,
                    start_new_session=True)
                time.sleep(delay)
                if proc.poll() is not None:
                    print(f"  {name} at {delay:.1f} s: finished first")
                    continue
                sent = time.monotonic()
                proc.send_signal(signum)
                _, err = proc.communicate(timeout=60)
                took = time.monotonic() - sent
                lines = err.decode().strip().splitlines()
                print(f"  {name} at {delay:.1f} s: stopped in {took:.3f} s, exit "
                      f"{proc.returncode}, {len(lines)} line(s) on stderr")
