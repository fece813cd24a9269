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
