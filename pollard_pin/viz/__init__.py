"""What people look at: ``viewer`` (MeshCat, static HTML), ``plots`` (matplotlib figures) and
``report`` (sizing table and cross-checks)."""
from .plots import write_figures
from .report import sizing_report
from .viewer import write_html

__all__ = ["write_figures", "write_html", "sizing_report"]
