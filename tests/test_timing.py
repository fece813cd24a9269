"""Wall-time instrumentation (timing.py): laps accumulate per stage into the sink, a None sink
records nothing, and the peak memory is this process's own."""
import time

from pollard_pin.timing import Stopwatch, peak_memory_mb


def test_laps_accumulate_per_stage():
    sink = {}
    w = Stopwatch(sink)
    time.sleep(0.02)
    w.lap("a")
    time.sleep(0.01)
    w.lap("b")
    time.sleep(0.02)
    w.lap("a")
    # sleep sleeps at least its time; a loaded machine may add to it
    assert set(sink) == {"a", "b"}
    assert 0.04 <= sink["a"] < 1.0 and 0.01 <= sink["b"] < 1.0


def test_lap_restarts_the_clock():
    sink = {}
    w = Stopwatch(sink)
    time.sleep(0.05)
    w.lap("slow")
    w.lap("fast")
    assert sink["fast"] < sink["slow"] / 5


def test_no_sink_records_nothing():
    w = Stopwatch(None)
    t = w.t
    w.lap("a")
    assert w.sink is None and w.t == t  # not even the clock moves


def test_peak_memory_grows_with_an_allocation():
    """VmHWM: after touching 64 MB more than ever before, the peak is at least that much
    higher (None where /proc is absent)."""
    before = peak_memory_mb()
    if before is None:
        return
    block = bytearray(int(before * 2**20) + 64 * 2**20)  # zero-filled: every page touched
    after = peak_memory_mb()
    del block
    assert after >= 2 * before + 60
