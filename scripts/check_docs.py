"""Before ``make docs``: the site's tools are importable, or one line says what to install.

    .venv/bin/python scripts/check_docs.py
"""
from __future__ import annotations

import importlib
import sys

TOOLS = ("sphinx", "myst_parser", "sphinx_gallery", "furo")


def main() -> int:
    missing = []
    for name in TOOLS:
        try:
            importlib.import_module(name)
        except ImportError:
            missing.append(name.replace("_", "-"))
    if missing:
        print(f"make docs: {', '.join(missing)} not installed: install the docs extra, "
              "pip install -e '.[docs]' (it needs the package registry)", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
