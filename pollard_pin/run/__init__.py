"""Run a trajectory through the pipeline: ``run.pipeline`` (the whole-trajectory solve and its
table), ``run.stream`` (window by window, in threads), ``run.stats`` (summary and duty
figures), ``run.stiffness`` (the stiffness and vibration along a run; its entry point
:func:`pollard_pin.stiffness` is not re-exported here, where it would hide the module)."""
from .pipeline import RunResult, run_pipeline, write_run_table
from .stats import RunStats, duty_figures, summary
from .stiffness import StiffnessRun, stream_stiffness
from .stream import STREAM_CHUNK, StreamOptions, solve_windows, stream_run, worker_robot

__all__ = ["STREAM_CHUNK", "RunResult", "RunStats", "StreamOptions", "duty_figures", "run_pipeline",
           "solve_windows", "stream_run", "summary", "worker_robot", "write_run_table",
           "StiffnessRun", "stream_stiffness"]
