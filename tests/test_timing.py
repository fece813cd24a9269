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
    """VmHWM: holding a block 64 MB larger than the peak so far, with every page written, the
    peak is at least the block's size (None where /proc is absent)."""
    before = peak_memory_mb()
    if before is None:
        return
    n = int((before + 64) * 2**20)
    block = bytearray(n)
    block[::4096] = b"\x01" * len(range(0, n, 4096))  # touch every page: resident
    after = peak_memory_mb()
    del block
    assert after >= before + 63
