"""A small part on a moving line for the paint and CLI tests (docs/model.md §24)."""


LINE_PART_TOML = """
[part]
mesh = "strip.stl"
position = [0.0, -0.45, 0.0]
facing = [-1.0, 0.0, 0.0]

[gun]
standoff = 0.15
sigma = 0.010
flow = 1.5e-7

[job]
thickness = 25e-6

[line]
speed = 0.03
direction = [0.0, 1.0, 0.0]
"""


def write_line_part(folder, speed: float = 0.03, position=(0.0, -0.45, 0.0),
                    width: float = 0.30):
    """A small part on a line, for tests: a ``width`` × 0.06 m strip (default 0.30 m) of
    radius 3 m (the shape of examples/parts/long_strip.stl, shorter) at ``position``, as a
    mesh and a job file in ``folder``; the job's path."""
    from pollard_pin.painting.workpiece import shapes

    shapes.curved_panel(radius=3.0, width=width, height=0.06, step=0.01).export(
        folder / "strip.stl")
    text = LINE_PART_TOML.replace("speed = 0.03", f"speed = {speed!r}").replace(
        "position = [0.0, -0.45, 0.0]", f"position = {list(position)!r}")
    (folder / "job.toml").write_text(text)
    return folder / "job.toml"
