"""The documentation site's sources (docs/, built by ``make docs``): every public name has an
entry in the API reference and every entry names something that exists; the Python blocks of
README.md, docs/getting_started.md and docs/guide.md run; the command-line reference lists every
command and option; the file-format page names every key the readers take; the citation file
carries the package's version; without the docs extra, ``make docs`` says so in one line."""
import re
import subprocess
import sys
from pathlib import Path

import pytest
from public_names import MISSING, lookup, public_names, public_objects

import pollard_pin

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
# ".. autofunction:: load" (under the page's last ``currentmodule``) or a full dotted name
AUTODOC = re.compile(r"^\.\. (auto(?:function|class|exception|data|module)|currentmodule)::"
                     r"\s+(\S+)(\n\s+:no-members:)?", re.M)


def _reference_targets() -> list[str]:
    """The full dotted name of every autodoc entry of docs/reference/*.rst; an automodule
    without ``:no-members:`` names its module and each member its ``__all__`` lists."""
    import importlib

    out = []
    for page in sorted((DOCS / "reference").glob("*.rst")):
        current = None
        for m in AUTODOC.finditer(page.read_text(encoding="utf-8")):
            kind, target = m.group(1), m.group(2)
            if kind == "currentmodule":
                current = target
                continue
            full = target if target.startswith("pollard_pin") or current is None \
                else f"{current}.{target}"
            out.append(full)
            if kind == "automodule" and not m.group(3):
                module = importlib.import_module(full)
                out += [f"{full}.{n}" for n in getattr(module, "__all__", ())]
    return out


def test_every_public_name_has_a_reference_entry():
    """Each public object (tests/public_names.py: the top level's and every subpackage's
    ``__all__``) has an entry under one of its public names or its defining module's."""
    documented = {id(lookup(t)) for t in _reference_targets()}
    missing = sorted(name for name, obj in public_objects().items()
                     if id(obj) not in documented)
    assert not missing, f"public names missing from docs/reference/*.rst: {missing}"


def test_the_reference_check_sees_subpackages():
    names = public_names()
    assert len(pollard_pin.__all__) <= 55 and len(names) > 150
    assert "pollard_pin.dynamics.drives.stiffness_at" in names
    assert "pollard_pin.painting.spray.Gun" in names
    assert "pollard_pin.kinematics.KinematicsInputError" in names


def test_every_reference_entry_exists():
    """A renamed or removed name fails here, before the build does."""
    stale = [target for target in _reference_targets() if lookup(target) is MISSING]
    assert not stale, f"reference entries that name nothing: {stale}"


def _python_blocks(path: Path) -> list[str]:
    return re.findall(r"^```python\n(.*?)^```", path.read_text(encoding="utf-8"), re.S | re.M)


# A 1,000,001-sample stream takes a minute: the guide's call, on fewer samples.
SHRINK = {"1_000_001": "20_001"}


@pytest.mark.parametrize("page", ["README.md", "docs/getting_started.md", "docs/guide.md"])
def test_python_blocks_run(page, tmp_path, monkeypatch, capsys):
    """Each page's blocks in order, in one namespace (a page's later blocks go on from its
    earlier ones), from a folder holding the repository's examples/ (~10 s for the guide)."""
    blocks = _python_blocks(ROOT / page)
    assert blocks, f"{page} has no Python block"
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    monkeypatch.chdir(tmp_path)
    namespace: dict = {"__name__": "__docs__"}
    for i, code in enumerate(blocks):
        for big, small in SHRINK.items():
            code = code.replace(big, small)
        exec(compile(code, f"{page} block {i + 1}", "exec"), namespace)
    if page == "README.md":  # what its comments say: "# 8.0 s, 1.0", "what `paint` writes"
        report = namespace["r"].report
        assert round(report.cycle_time, 1) == 8.0
        assert report.thickness["within_10pct"] == 1.0
        assert (tmp_path / "paint" / "paint.json").is_file()


def _cli_reference() -> str:
    sys.path.insert(0, str(DOCS / "_ext"))
    try:
        from cli_text import cli_reference
    finally:
        sys.path.remove(str(DOCS / "_ext"))
    from pollard_pin.cli import build_parser

    return "\n".join(cli_reference(build_parser()))


def test_cli_reference_lists_every_command_and_option():
    import argparse

    from pollard_pin.cli import build_parser

    text = _cli_reference()
    parser = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    missing = []
    for name, command in sub.choices.items():
        if f"``pollard-pin {name}``" not in text:
            missing.append(name)
        for action in command._actions:
            missing += [f"{name} {s}" for s in action.option_strings if f"``{s}" not in text]
    assert not missing, f"not in the command-line reference: {missing}"
    # a default as the parser has it, and the help text expanded
    run = sub.choices["run"]
    samples = next(a for a in run._actions if "--samples" in a.option_strings)
    section = text.split("``pollard-pin run``")[1].split("``pollard-pin ")[0]
    assert f"``--samples {samples.metavar or 'SAMPLES'}``" in section
    assert "%(" not in text


def test_formats_page_names_every_key_the_readers_take():
    from pollard_pin.dynamics.motors import KEYS, OPTIONAL
    from pollard_pin.painting.cell.robots import ROBOT_KEYS
    from pollard_pin.painting.job import OPTIONAL as JOB_OPTIONAL
    from pollard_pin.painting.job import PART_OPTIONAL, PART_REQUIRED, REQUIRED
    from pollard_pin.painting.line.conveyor import LINE_KEYS
    from pollard_pin.painting.material import OPTIONAL as PAINT_OPTIONAL
    from pollard_pin.painting.material import REQUIRED as PAINT_REQUIRED

    text = (DOCS / "formats.md").read_text(encoding="utf-8")
    tables = {name: REQUIRED[name] + JOB_OPTIONAL[name] for name in REQUIRED}
    tables |= {"part": PART_REQUIRED + PART_OPTIONAL, "line": LINE_KEYS,
               "[robot]": ROBOT_KEYS, "actuators": KEYS + OPTIONAL,
               "paint": PAINT_REQUIRED + PAINT_OPTIONAL}
    missing = []
    for table, keys in tables.items():
        # each table's keys are the rows of the table under its heading
        heading = f"`[{table}]`:" if table != "actuators" else "### Actuators TOML"
        assert heading in text, heading
        section = re.split(r"\n\n`\[|\n#", text.split(heading, 1)[1], maxsplit=1)[0]
        missing += [f"{table}.{k}" for k in keys if f"| `{k}`" not in section]
    assert not missing, f"keys missing from docs/formats.md: {missing}"


def test_readme_plot_table_lists_every_file_plot_writes():
    """The README's table under ``plot`` lists each figure `pollard-pin plot` writes (the
    trajectory's and the joint loads'), and no other."""
    from pollard_pin.viz.plots import FIGURES, LOAD_FIGURES

    text = (ROOT / "README.md").read_text(encoding="utf-8")
    table = text.split("* **`plot`**", 1)[1].split("* **`", 1)[0]
    listed = set(re.findall(r"`(\w+)\.png`", table))
    assert listed == set(FIGURES + LOAD_FIGURES)


def test_citation_carries_the_version():
    cff = (ROOT / "CITATION.cff").read_text(encoding="utf-8")
    assert re.search(r'^version: "(.*)"$', cff, re.M).group(1) == pollard_pin.__version__
    assert f"version {pollard_pin.__version__}" in (DOCS / "citing.md").read_text("utf-8")


def test_make_docs_without_the_docs_extra_says_so_in_one_line():
    prelude = "import sys; sys.modules['sphinx'] = None\nimport runpy\n"
    r = subprocess.run([sys.executable, "-c", prelude + "runpy.run_path("
                        f"{str(ROOT / 'scripts' / 'check_docs.py')!r}, run_name='__main__')"],
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 1 and r.stdout == ""
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in r.stderr, r.stderr
    assert "sphinx" in lines[0] and "pip install -e '.[docs]'" in lines[0]


def _layout_entries(guide: str) -> dict[str, str]:
    """The guide's package layout map: {top-level entry ("painting/", "errors.py"): its text}."""
    block = guide.split("## Package layout", 1)[1].split("```", 2)[1]
    entries: dict[str, str] = {}
    current = None
    for line in block.splitlines():
        m = re.match(r"^  (\w+(?:/|\.py))(?:\s|$)", line)
        if m:
            current = m.group(1)
            entries[current] = line
        elif current:
            entries[current] += "\n" + line
    return entries


def _unmapped(folders, entries: dict[str, str]) -> list[str]:
    """The package folders (relative, "painting/cell") the map does not show: a top-level
    folder is an entry, a deeper one is named ("cell/") in its top-level folder's entry."""
    missing = []
    for folder in folders:
        top, *rest = folder.split("/")
        text = entries.get(f"{top}/")
        if text is None or any(not re.search(rf"(?<![\w/]){re.escape(p)}/", text)
                               for p in rest):
            missing.append(folder)
    return missing


def test_every_package_folder_is_in_the_guides_layout_map():
    """Every directory under pollard_pin/ with an ``__init__.py`` appears in docs/guide.md's
    layout map (folders → map: the map may name what is planned)."""
    package = ROOT / "pollard_pin"
    folders = sorted(str(p.parent.relative_to(package)) for p in package.rglob("__init__.py")
                     if p.parent != package)
    assert "painting/cell" in folders and "dynamics/drives" in folders
    entries = _layout_entries((DOCS / "guide.md").read_text(encoding="utf-8"))
    missing = _unmapped(folders, entries)
    assert not missing, f"package folders missing from docs/guide.md's layout map: {missing}"


def test_the_layout_check_can_fail():
    entries = {"painting/": "  painting/     api.py; spray/ deposition.py;\n  workpiece/ mesh.py",
               "io/": "  io/  atomic.py"}
    assert _unmapped(["painting/spray", "painting/workpiece", "io"], entries) == []
    assert _unmapped(["painting/cell", "viz", "io/spray"], entries) == [
        "painting/cell", "viz", "io/spray"]
