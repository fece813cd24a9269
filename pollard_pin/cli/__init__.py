"""The pollard-pin command line: ``main`` (parser assembly, errors, signals) in :mod:`.main`,
shared argument types and steps in :mod:`.common`, one module per command."""
from .main import build_parser, main

__all__ = ["main", "build_parser"]
