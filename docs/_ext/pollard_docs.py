"""Sphinx glue for the pollard-pin site.

- ``§N`` anchors: every ``## N. Title`` heading of docs/model.md gets the label ``sN`` (the
  page's HTML anchor ``model.html#sN``), added when the page is read, so that the Markdown file
  stays as GitHub shows it and new sections get their anchor with no edit here.
- ``docs/model.md §N`` in a docstring becomes a link to that section; a bare ``§N`` in the
  model document itself links too (``thesis §4.1`` and other dotted numbers are the thesis').
- A reference to a public name through the module that defines it
  (``pollard_pin.model.build.load``, ``.closure.solve_closure``, ``Margins``) resolves to its
  entry under its public name (the top level's or its subpackage's ``__all__``) when it is the
  same object; a name of the package that the
  reference does not list shows as code; a name that exists nowhere fails the build
  (``nitpicky``).
- Docstrings, before napoleon reads them: ``|x|`` (an absolute value) is no substitution, and
  a property's first line is text, not napoleon's ``type: text``.
- ``.. cli-reference::`` writes the command-line reference from ``build_parser()``.
"""
from __future__ import annotations

import functools
import importlib
import os
import re
import shutil
import sys
from pathlib import Path

from cli_text import cli_reference
from docutils import nodes
from docutils.statemachine import StringList
from dotted import MISSING, lookup
from sphinx.util.docutils import SphinxDirective
from sphinx.util.nodes import nested_parse_with_titles

HEADING = re.compile(r"^## (\d+)\. ")
# an integer section (not a thesis' dotted one), not right after "thesis " and not in code
BARE_SECTION = re.compile(r"(?<![\w.`§])(?<!thesis )§(\d+)(?![\d.]*\d)(?!\.\d)")
DOCSTRING_CITE = re.compile(r"(?<![`<])docs/model\.md §(\d+)")
MARKDOWN_CITE = re.compile(r"(?<!\[)docs/model\.md §(\d+)(?!\d)")
ROOT = Path(__file__).resolve().parents[2]  # the checkout: pollard_pin/ beside docs/


# -- the model document's § anchors ----------------------------------------------------------

def _model_source(app, docname, source):
    if docname.startswith("auto_tutorials/"):  # the gallery's RST: text lines, not code
        source[0] = "\n".join(line if line[:1].isspace() else _cite_link(line)
                               for line in source[0].splitlines()) + "\n"
    if docname != "model":
        if app.env.doc2path(docname).suffix == ".md":
            source[0] = _markdown_cites(source[0])
        return
    out, fenced = [], False
    for line in source[0].splitlines():
        if line.startswith("```"):
            fenced = not fenced
        elif not fenced:
            m = HEADING.match(line)
            if m:
                out += [f"(s{m.group(1)})=", ""]
            elif not line.startswith("    "):
                line = _link_sections(line)
        out.append(line)
    source[0] = "\n".join(out) + "\n"


def _markdown_cites(text: str) -> str:
    """A Markdown page's ``docs/model.md §N`` (outside code and links) links to section N."""
    out, fenced = [], False
    for line in text.splitlines():
        if line.startswith("```"):
            fenced = not fenced
        elif not fenced:
            parts = line.split("`")
            parts[::2] = [MARKDOWN_CITE.sub(
                lambda m: f"{{ref}}`{m.group(0)} <s{m.group(1)}>`"
                if m.group(1) in _model_sections() else m.group(0), p) for p in parts[::2]]
            line = "`".join(parts)
        out.append(line)
    return "\n".join(out) + "\n"


def _link_sections(line: str) -> str:
    """``§N`` outside inline code becomes a MyST link to the section's label (a section still
    to be written stays text)."""
    parts = line.split("`")
    for i in range(0, len(parts), 2):  # the even parts lie outside code spans
        parts[i] = BARE_SECTION.sub(lambda m: f"[§{m.group(1)}](#s{m.group(1)})"
                                    if m.group(1) in _model_sections() else m.group(0), parts[i])
    return "`".join(parts)


def _cite_link(line: str) -> str:
    """``docs/model.md §N`` as a link to section N, where the model document has it (a cite of
    a section still to be written stays text: tests/test_repository.py names it)."""
    return DOCSTRING_CITE.sub(lambda m: f":ref:`{m.group(0)} <s{m.group(1)}>`"
                              if m.group(1) in _model_sections() else m.group(0), line)


@functools.cache
def _model_sections() -> frozenset[str]:
    text = (ROOT / "docs" / "model.md").read_text(encoding="utf-8")
    return frozenset(m.group(1) for m in re.finditer(r"^## (\d+)\. ", text, re.M))


def _docstrings(app, what, name, obj, options, lines):
    """Before napoleon: the cites become links, ``|x|`` (an absolute value, as the docstrings
    write it) is no substitution, and a property's first line is text, not ``type: text``."""
    for i, line in enumerate(lines):
        line = _cite_link(line)
        row = line.strip()
        if not (row.startswith(("+-", "+=")) or row[:1] == row[-1:] == "|"):  # not a table's
            parts = line.split("``")
            parts[::2] = [p.replace("|", r"\|") for p in parts[::2]]
            line = "``".join(parts)
        lines[i] = line
    if what in ("property", "attribute", "data") and lines:
        lines[:0] = ["..", ""]  # an empty comment: napoleon reads no type from the first line


# -- public names reached through their defining module ---------------------------------------

@functools.cache
def _public_entries() -> dict[int, tuple[str, ...]]:
    """{id(object): its public full names}: the top level's ``__all__``, then every
    subpackage's (the names tests/public_names.py checks the reference for)."""
    import pollard_pin

    names = [f"pollard_pin.{n}" for n in pollard_pin.__all__]
    for init in sorted((ROOT / "pollard_pin").rglob("__init__.py")):
        package = ".".join(init.parent.relative_to(ROOT).parts)
        if package != "pollard_pin":
            module = importlib.import_module(package)
            names += [f"{package}.{n}" for n in getattr(module, "__all__", ())]
    out: dict[int, tuple[str, ...]] = {}
    for full in names:
        obj = lookup(full)
        if obj is not MISSING:
            out[id(obj)] = out.get(id(obj), ()) + (full,)
    return out


def _public_targets(full: str) -> tuple[str, ...]:
    """The public names of the object ``full`` names (``pollard_pin.model.build.load`` →
    ``pollard_pin.load``; a class's member through its class's public name), or ()."""
    parts = full.split(".")
    for i in range(len(parts), 1, -1):
        obj = lookup(".".join(parts[:i]))
        if obj is not MISSING:
            rest = parts[i:]
            return tuple(".".join([p, *rest]) for p in _public_entries().get(id(obj), ()))
    return ()


def _missing_reference(app, env, node, contnode):
    """A name documented in the reference, seen from the docstring's module, links to it; a
    public name through its module links to its ``pollard_pin.*`` entry; a name of the package
    that the reference does not list shows as code; a short name found nowhere else links to
    the one documented object whose name it ends. Anything else (a misspelt or removed name)
    stays missing and fails the build."""
    if node.get("refdomain") != "py":
        return None
    target = node["reftarget"].lstrip("~")
    domain = env.get_domain("py")
    candidates = _candidates(target, _source_module(node), node.get("py:class"))
    for full in candidates:
        if full != target and full in domain.objects:
            return _resolve(app, env, node, contnode, full)
    for full in candidates:
        for public in _public_targets(full):
            if public != target and public in domain.objects:
                resolved = _resolve(app, env, node, contnode, public)
                if resolved is not None:
                    return resolved
    if any(_exists(full) for full in candidates):
        if os.environ.get("POLLARD_DOCS_UNLISTED"):  # which package names the reference lacks
            print(f"unlisted: {target} (from {candidates[0]})", file=sys.stderr)
        return contnode
    # a name only the type checker imports (``if TYPE_CHECKING:``), as in annotations
    ends = [name for name in domain.objects if name.endswith("." + target.lstrip("."))]
    # an entry and its canonical alias (autodoc adds the defining module's name) are one
    # object: the shorter, public name
    objects = [lookup(name) for name in ends]
    if len(ends) == 1 or (len({id(o) for o in objects}) == 1 and MISSING not in objects):
        return _resolve(app, env, node, contnode, min(ends, key=len))
    return None


def _resolve(app, env, node, contnode, target):
    node = node.deepcopy()
    node["reftarget"], node["refspecific"] = target, False
    return env.get_domain("py").resolve_xref(env, node["refdoc"], app.builder, node["reftype"],
                                             target, node, contnode)


def _source_module(node) -> str | None:
    """The module whose docstring holds the reference (autodoc names its file)."""
    m = re.match(r"(.*?\.py):docstring of ", node.source or "")
    if not m:
        return None
    try:
        parts = Path(m.group(1)).resolve().relative_to(ROOT).with_suffix("").parts
    except ValueError:
        return None
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _candidates(target: str, module: str | None, cls: str | None) -> list[str]:
    """Full names that ``target`` may mean, seen from ``module`` (innermost first)."""
    name = target.lstrip(".")
    if name.startswith("pollard_pin."):
        return [name]
    out = []
    scope = (module or "pollard_pin").split(".")
    for i in range(len(scope), 0, -1):
        prefix = ".".join(scope[:i])
        if cls and i == len(scope):
            out.append(f"{prefix}.{cls.split('.')[-1]}.{name}")
        out.append(f"{prefix}.{name}")
    return out


def _exists(full: str) -> bool:
    """Whether ``full`` names a module, or an attribute (a class's field too) of one."""
    parts = full.split(".")
    for i in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:i]))
        except ImportError:
            continue
        for part in parts[i:]:
            fields = getattr(obj, "__annotations__", {}) if isinstance(obj, type) else {}
            if hasattr(obj, part):
                obj = getattr(obj, part)
            elif part in fields:
                obj = None
            else:
                return False
        return True
    return False


# -- the command-line reference -------------------------------------------------------------

class CliReference(SphinxDirective):
    """Every command of ``pollard-pin``, its usage, options, defaults and help."""

    def run(self):
        from pollard_pin.cli.main import build_parser

        lines = cli_reference(build_parser())
        node = nodes.section()
        node.document = self.state.document
        nested_parse_with_titles(self.state, StringList(lines, "cli-reference"), node)
        return node.children


# -- files the tutorials write for their pages ----------------------------------------------

def _tutorial_files(app, exception):
    """A page a tutorial writes beside itself (sphinx-gallery runs it in docs/tutorials/), such
    as the viewer's HTML, goes beside the tutorial's page, where its link points."""
    src, dst = Path(app.srcdir) / "tutorials", Path(app.outdir) / "auto_tutorials"
    if exception is not None or app.builder.format != "html" or not dst.is_dir():
        return
    for page in src.glob("*.html"):
        shutil.copy2(page, dst / page.name)


def setup(app):
    app.connect("source-read", _model_source)
    app.connect("autodoc-process-docstring", _docstrings, priority=400)
    app.connect("missing-reference", _missing_reference)
    app.add_directive("cli-reference", CliReference)
    app.connect("build-finished", _tutorial_files)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
