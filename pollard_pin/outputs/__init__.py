"""Paint's outputs read back, a layer above the figures and below the commands: paint.json's
schema (:mod:`.schema`: the one writer of its text, the one reader) and a paint output folder
(:mod:`.folder`: its files, its report, its film, a cell's robots; :mod:`.overlay`: the
viewer's drawing of it), and the paint result that writes itself (:mod:`.result`:
:func:`~pollard_pin.paint`, :class:`~pollard_pin.PaintResult`) with its writers
(:mod:`.paint_files`, a cell's :mod:`.paint_cell_files`, :mod:`.robots_toml`)."""
from .folder import PaintFolderError, read_report
from .result import PaintResult, fewest_robots, paint, write_result
from .robots_toml import write_robots
from .schema import PaintJson, dumps, read_paint_json

__all__ = ["paint", "PaintResult", "fewest_robots", "write_result", "PaintJson",
           "read_paint_json", "dumps", "read_report", "PaintFolderError", "write_robots"]
