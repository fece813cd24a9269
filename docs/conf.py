"""Sphinx configuration of the pollard-pin site (``make docs`` → build/docs/index.html)."""
from __future__ import annotations

import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))
sys.path.insert(0, str(HERE.parent))  # the checkout's pollard_pin, as the tests import it

import pollard_pin  # noqa: E402

project = "pollard-pin"
author = "the pollard-pin authors"
copyright = "2026, the pollard-pin authors"
release = version = pollard_pin.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "myst_parser",
    "sphinx_gallery.gen_gallery",
    "pollard_docs",
]
smartquotes = False  # "--out" stays two hyphens, as typed; the pages write their own dashes
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "tutorials", "Thumbs.db", ".DS_Store"]
templates_path: list[str] = []

# A broken :func:/:class: fails the build (make docs runs with -W --keep-going).
nitpicky = True
nitpick_ignore_regex = [
    # third-party and builtin types named in signatures and docstrings: not ours to document
    ("py:.*", r"(numpy|np|pinocchio|pin|polars|pl|pyarrow|trimesh|toppra|mujoco|meshcat|scipy"
              r"|matplotlib|dask|distributed|argparse|pathlib|os|io|typing|collections"
              r"|concurrent|multiprocessing|logging)(\..*)?"),
    ("py:.*", r"(ndarray|ArrayLike|NDArray|Path|PathLike|Callable|Iterable|Iterator|Sequence"
              r"|Mapping|Any|Self|Figure|Axes|Client|DataFrame|Trimesh|Table|TextIO|IO)"),
]

# -- autodoc and napoleon (numpydoc-style docstrings) ---------------------------------------
autodoc_member_order = "bysource"
autodoc_typehints = "description"
autodoc_typehints_format = "short"
autodoc_preserve_defaults = True
autodoc_default_options = {"members": True, "show-inheritance": True}
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_rtype = False
napoleon_preprocess_types = True

# -- MyST (docs/model.md, docs/verification.md, docs/guide.md and the site's pages) --------
myst_enable_extensions = ["dollarmath", "amsmath", "deflist", "colon_fence", "attrs_inline"]
myst_heading_anchors = 3  # GitHub's heading ids: guide.md's links into model.md keep working
myst_dmath_double_inline = True

# -- the tutorials (docs/tutorials/*.py, executed at build time) ----------------------------
_HEADERS = ("README.rst", "README.txt", "GALLERY_HEADER.rst")
if any((HERE / "tutorials" / name).is_file() for name in _HEADERS):
    sphinx_gallery_conf = {
        "examples_dirs": "tutorials",
        "gallery_dirs": "auto_tutorials",
        "filename_pattern": r"/plot_",  # every plot_*.py executes
        "ignore_pattern": r"__init__\.py",
        "within_subsection_order": "FileNameSortKey",
        "download_all_examples": False,
        "remove_config_comments": True,
        "abort_on_example_error": False,
        "only_warn_on_example_error": False,
        "matplotlib_animations": False,
        "image_scrapers": ("matplotlib",),
        "show_memory": False,
        # the tutorials' code links to the reference: pp.load → pollard_pin.load
        "reference_url": {"pollard_pin": None},
        "doc_module": ("pollard_pin",),
        "backreferences_dir": "auto_tutorials/backreferences",
        "promote_jupyter_magic": False,
    }
else:  # a checkout without the tutorials: the page says so instead of failing the build
    extensions.remove("sphinx_gallery.gen_gallery")
    (HERE / "auto_tutorials").mkdir(exist_ok=True)
    (HERE / "auto_tutorials" / "index.rst").write_text(
        "Tutorials\n=========\n\nThis checkout has no ``docs/tutorials/``.\n")

os.environ.setdefault("MPLBACKEND", "Agg")
os.environ.setdefault("DASK_LOGGING__DISTRIBUTED", "warning")  # a tutorial's LocalCluster, quiet

# -- HTML --------------------------------------------------------------------------------
html_theme = "furo"
html_title = f"pollard-pin {release}"
html_static_path: list[str] = []
html_show_sourcelink = False
