"""Run a trajectory through the pipeline: ``run.pipeline`` (the whole-trajectory solve and its
table), ``run.stream`` (window by window, in threads), ``run.stats`` (summary and duty
figures), ``run.stiffness`` (the stiffness and vibration along a run; its entry point
:func:`pollard_pin.stiffness` is not re-exported here, where it would hide the module)."""
from .pipeline import RunResult, run_pipeline, write_run_table
from .stiffness import StiffnessRun, stream_stiffness
from .stream import StreamOptions, stream_run

__all__ = ["RunResult", "StreamOptions", "run_pipeline", "stream_run", "write_run_table",
           "StiffnessRun", "stream_stiffness"]
