"""pollard-pin paint of a job with a [line]: the panel or part rides a conveyor
(docs/model.md §24); what ``view --paint`` moves with it."""
from __future__ import annotations

from pathlib import Path


def riding(line, folder: Path) -> dict:
    """The viewer's moving nodes of a line's paint folder: the film (a panel's or a part's)
    carried by the line (translation speed·t·direction at path time t, docs/model.md §24),
    the line read by the job's rule (paint.line_job: 0 < speed ≤ 2 m/s, a direction)."""
    from collections.abc import Mapping

    import numpy as np

    from ..io.table import ResultFileError
    from ..painting.line.conveyor import LINE_KEYS, line_from_table
    from ..viz.viewer import ROOT

    table = {k: line[k] for k in LINE_KEYS if k in line} if isinstance(line, Mapping) else line
    conveyor = line_from_table(str(folder / "paint.json"), table, ResultFileError)
    speed, e = conveyor.speed, np.asarray(conveyor.direction)

    def place(t: float) -> np.ndarray:
        T = np.eye(4)
        T[:3, 3] = speed * t * e
        return T

    return {f"{ROOT}/paint": place}
