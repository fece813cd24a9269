"""Wall-time instrumentation for the benchmark: stages accumulate seconds into a dict."""
from __future__ import annotations

import time


class Stopwatch:
    """Accumulates wall time per stage into ``sink`` (a dict) — or does nothing if it is None."""

    def __init__(self, sink: dict | None):
        self.sink = sink
        self.t = time.perf_counter()

    def lap(self, stage: str) -> None:
        if self.sink is not None:
            now = time.perf_counter()
            self.sink[stage] = self.sink.get(stage, 0.0) + now - self.t
            self.t = now


def peak_memory_mb() -> float | None:
    """This process's peak resident memory [MB]: VmHWM of /proc/self/status (Linux; it belongs
    to the process's own address space, so unlike ``ru_maxrss`` it does not include the
    parent that spawned it), else None."""
    try:
        with open("/proc/self/status", encoding="ascii") as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) / 1024.0
    except (OSError, ValueError):
        pass
    return None
