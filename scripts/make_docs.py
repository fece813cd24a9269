"""Regenerate the README's pictures: docs/viewer.png (the static MeshCat page rendered in
headless Chromium), docs/film_view.png (``view --paint`` of the ribbed plate's film: its default
view and legend) and docs/plots/*.png (``pollard-pin plot`` of the thesis trajectory).

    .venv/bin/python scripts/make_docs.py

Needs Debian's ``chromium`` for the screenshot.
"""
import sys
import tempfile
from pathlib import Path

import pollard_pin as pp

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))  # the headless-browser helper is a test utility
from browser import capture_meshcat, find_chromium  # noqa: E402

DOCS = ROOT / "docs"


def main():
    if find_chromium() is None:  # check before writing anything
        sys.exit("make_docs: the viewer screenshot needs Chromium, which is not installed "
                 "(Debian: apt-get install chromium; or set POLLARD_CHROMIUM=/path/to/chrome)")
    robot = pp.load()
    result = pp.run_pipeline(robot, pp.thesis_trajectory(), loads=True)  # + joint_loads.png
    for path in pp.write_figures(result, DOCS / "plots", dpi=72):
        print(f"wrote {path} ({path.stat().st_size // 1024} kB)")
    with tempfile.TemporaryDirectory() as tmp:
        html = pp.write_html(Path(tmp) / "pollard.html", robot, result.ik, frames=True)
        png = DOCS / "viewer.png"
        facts = capture_meshcat(html, png, width=1100, height=640, time_s=10.0)
    print(f"wrote {png} ({png.stat().st_size // 1024} kB; {facts['meshes']} meshes, "
          f"{facts['duration']} s animation, renderer {facts['renderer']})")
    film_view()


def film_view():
    """docs/film_view.png: the ribbed plate's paint folder (the rib's shadow) in the static
    viewer as it opens (the default view of the painted faces, the film's legend), at 4 s."""
    import subprocess

    with tempfile.TemporaryDirectory() as tmp:
        out, html = Path(tmp) / "paint", Path(tmp) / "film.html"
        job = ROOT / "examples" / "parts" / "ribbed_plate.toml"
        for argv in (["paint", "--job", str(job), "--out", str(out)],
                     ["view", "--paint", str(out), "--html", str(html), "--fps", "5"]):
            if subprocess.run([sys.executable, "-m", "pollard_pin.cli", *argv]).returncode:
                sys.exit(f"make_docs: pollard-pin {argv[0]} of {job.name} failed")
        png = DOCS / "film_view.png"
        capture_meshcat(html, png, width=1100, height=640, time_s=4.0, controls=False)
    print(f"wrote {png} ({png.stat().st_size // 1024} kB)")


if __name__ == "__main__":
    main()
