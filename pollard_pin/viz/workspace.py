"""The plane workspace map as a figure (docs/model.md §22): reachable points coloured by their
smallest margin min(|sin θ1716|, σ_parallel, σ_serial), unreachable points by their reason,
and the largest reachable rectangle outlined. It draws a :class:`~..workspace.grid.
WorkspaceMap`; it computes nothing. Matplotlib's object API (no pyplot, no backend switch)."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

# Unreachable points: one muted colour per reason present (cycled), drawn under the margins.
REASON_COLOURS = ("#d9d9d9", "#fdd0a2", "#c6dbef", "#fcbba1", "#c7e9c0", "#dadaeb",
                  "#fee391", "#f2c4de", "#bdbdbd", "#a1d99b", "#9ecae1", "#fc9272")


def workspace_figure(ws):
    """A matplotlib Figure of a plane map. Artists carry gids: ``margin`` (the image),
    ``rectangle``, ``reason_<code>`` (legend patches)."""
    from matplotlib.colors import Normalize
    from matplotlib.figure import Figure
    from matplotlib.patches import Patch
    from matplotlib.patches import Rectangle as Box

    grid = ws.grid
    if len(grid.axes) != 2:
        raise ValueError("the workspace figure draws a plane map (volume maps have none)")
    names = [("x", "y", "z")[a] for a in grid.axes]
    reason = ws.image("reason").T  # rows: the second axis (vertical)
    margin = ws.smallest_margin.reshape(grid.shape).T
    reach = reason == 0
    norm = Normalize(0.0, float(np.nanmax(np.where(reach, margin, np.nan))))
    from matplotlib import colormaps

    cmap = colormaps["viridis"]
    rgba = np.ones(reason.shape + (4,))
    present = [int(c) for c in np.unique(reason) if c != 0]
    for i, code in enumerate(present):
        rgba[reason == code] = _rgba(REASON_COLOURS[i % len(REASON_COLOURS)])
    rgba[reach] = cmap(norm(margin[reach]))
    h = grid.step
    x0, y0 = grid.coordinates(0), grid.coordinates(1)
    extent = (x0[0] - h / 2, x0[-1] + h / 2, y0[0] - h / 2, y0[-1] + h / 2)
    fig = Figure(figsize=(9, 7.5), constrained_layout=True)
    ax = fig.add_subplot()
    img = ax.imshow(rgba, origin="lower", extent=extent, interpolation="nearest")
    img.set_gid("margin")
    from matplotlib.cm import ScalarMappable

    bar = fig.colorbar(ScalarMappable(norm, cmap), ax=ax, shrink=0.8)
    bar.set_label("smallest margin min(|sin θ1716|, σ_parallel, σ_serial), reachable points")
    handles = []
    for i, code in enumerate(present):
        p = Patch(color=REASON_COLOURS[i % len(REASON_COLOURS)],
                  label=f"{ws.reasons[code]} ({int((reason == code).sum())})")
        p.set_gid(f"reason_{code}")
        handles.append(p)
    rect = ws.rectangle
    if rect is not None:
        lo = [rect.low[a] for a in grid.axes]
        box = Box((lo[0], lo[1]), rect.size[0], rect.size[1], fill=False,  # corner points
                  edgecolor="crimson", lw=2,
                  label=f"largest rectangle {rect.size[0]:.3g} × {rect.size[1]:.3g} m")
        box.set_gid("rectangle")
        ax.add_patch(box)
        handles.append(box)
    fig.legend(handles=handles, fontsize=7, loc="outside lower center", ncol=3,
              title="unreachable: first reason", title_fontsize=8)
    ax.set_xlabel(f"{names[0]} [m]")
    ax.set_ylabel(f"{names[1]} [m]")
    s = ws.summary
    fixed = s["grid"]["plane"]
    deg = ", ".join(f"{math.degrees(a):.3g}" for a in ws.orientation)
    ax.set_title(f"Workspace at {', '.join(f'{k} = {v:g} m' for k, v in fixed.items())}, "
                 f"(ψ, θ, φ) = ({deg})°\narea {s['area']:.4g} m², global conditioning "
                 f"index {s['global_conditioning_index']:.3g}", fontsize=10)
    ax.set_aspect("equal")
    box_lo, box_hi = (np.asarray(s["bounding_box"][k]) for k in ("low", "high"))
    pad = np.maximum(0.1, 0.2 * (box_hi - box_lo))  # the reachable region and its surround
    for i, (a, setter) in enumerate(zip(grid.axes, (ax.set_xlim, ax.set_ylim))):
        setter(max(extent[2 * i], box_lo[a] - pad[a]), min(extent[2 * i + 1], box_hi[a] + pad[a]))
    return fig


# the stiffness panels (docs/model.md §27.6): column, label, scale to the shown unit
STIFFNESS_PANELS = (("kmin", "kmin [kN/m], softest tip stiffness", 1e-3),
                    ("f1", "f1 [Hz], lowest natural frequency", 1.0),
                    ("sag", "sag [µm], the tip's displacement under the weight", 1e6))


def stiffness_figure(ws):
    """A matplotlib Figure of a plane map's stiffness columns (kmin, f1, sag) side by side,
    unreachable points blank. Each image carries the gid of its column."""
    from matplotlib.figure import Figure

    grid = ws.grid
    if len(grid.axes) != 2 or ws.columns is None or "kmin" not in ws.columns:
        raise ValueError("the stiffness figure draws a plane map made with stiffnesses")
    names = [("x", "y", "z")[a] for a in grid.axes]
    h = grid.step
    x0, y0 = grid.coordinates(0), grid.coordinates(1)
    extent = (x0[0] - h / 2, x0[-1] + h / 2, y0[0] - h / 2, y0[-1] + h / 2)
    lo, hi = (np.asarray(ws.summary["bounding_box"][k]) for k in ("low", "high"))
    fig = Figure(figsize=(15, 4.4), constrained_layout=True)
    for i, (col, label, scale) in enumerate(STIFFNESS_PANELS):
        ax = fig.add_subplot(1, 3, i + 1)
        img = ax.imshow(scale * ws.image(col).T, origin="lower", extent=extent,
                        interpolation="nearest", cmap="viridis")
        img.set_gid(col)
        fig.colorbar(img, ax=ax, shrink=0.8).set_label(label)
        ax.set_xlabel(f"{names[0]} [m]")
        ax.set_ylabel(f"{names[1]} [m]")
        ax.set_aspect("equal")
        for a, setter in zip(grid.axes, (ax.set_xlim, ax.set_ylim)):
            setter(lo[a] - h, hi[a] + h)
    fixed = ws.summary["grid"]["plane"]
    deg = ", ".join(f"{math.degrees(a):.3g}" for a in ws.orientation)
    fig.suptitle(f"Stiffness at {', '.join(f'{k} = {v:g} m' for k, v in fixed.items())}, "
                 f"(ψ, θ, φ) = ({deg})°: compliant drives, rigid links (docs/model.md §27)",
                 fontsize=10)
    return fig


def write_stiffness_png(ws, path, dpi: int = 100) -> Path:
    """Write :func:`stiffness_figure` to ``path`` (PNG), atomically."""
    from .plots import save_png

    return save_png(stiffness_figure(ws), path, dpi)


def _rgba(hex_colour: str) -> tuple:
    from matplotlib.colors import to_rgba

    return to_rgba(hex_colour)


def write_workspace_png(ws, path, dpi: int = 100) -> Path:
    """Write :func:`workspace_figure` to ``path`` (PNG), atomically."""
    from .plots import save_png

    return save_png(workspace_figure(ws), path, dpi)


def workspace_cloud(folder) -> tuple[np.ndarray, np.ndarray]:
    """(points (n, 3) [m], colours (n, 3)) of the reachable points of a workspace map written
    to ``folder`` (``workspace.csv`` or ``.parquet``), coloured by the local conditioning index
    (viridis, 0 to its maximum): the viewer's point cloud (``view --workspace``)."""
    from matplotlib import colormaps

    from ..io.table import ResultFileError, read_result
    from .viewer import ViewerError, check_scene_points

    folder = Path(folder)
    if not folder.is_dir():
        raise ResultFileError(f"{folder}: " + ("is a file, not a folder" if folder.exists() else
                                               "no such folder") + " (write a workspace map "
                              "with pollard-pin workspace --out FOLDER)")
    found = [folder / f"workspace.{ext}" for ext in ("parquet", "csv")
             if (folder / f"workspace.{ext}").is_file()]
    if not found:
        raise ResultFileError(f"{folder}: no workspace.csv or workspace.parquet (write one with "
                              "pollard-pin workspace --out FOLDER)")
    if len(found) > 1:  # pollard-pin workspace never leaves both: which map is meant?
        raise ResultFileError(f"{folder}: holds both workspace.csv and workspace.parquet, two "
                              "different maps perhaps: remove the one not meant")
    table = read_result(found[0])
    missing = [c for c in ("x", "y", "z", "reachable", "conditioning") if c not in table.columns]
    if missing:
        raise ResultFileError(f"{found[0]}: not a workspace table (no column {missing[0]!r})")
    flag = table["reachable"]
    odd = (flag != 0) & (flag != 1)
    if odd.any():
        k = int(np.argmax(odd))
        raise ResultFileError(f"{found[0]}: row {k + 1}: reachable = {flag[k]:.4g}, expected 0 "
                              "or 1")
    ok = flag == 1
    pts = np.stack([table[c][ok] for c in ("x", "y", "z")], axis=1)
    index = table["conditioning"][ok]
    bad = ~np.isfinite(np.column_stack([pts, index])).all(axis=1)
    if bad.any():  # a reachable point has a position and an index: a damaged table
        row = int(np.flatnonzero(ok)[np.argmax(bad)]) + 1
        raise ResultFileError(f"{found[0]}: row {row}: a reachable point with a non-finite "
                              "x, y, z or conditioning")
    rows = np.flatnonzero(ok) + 1
    out = (index < 0) | (index > 1)
    if out.any():  # σ_min/σ_max-like: between 0 and 1 (docs/model.md §22)
        k = int(np.argmax(out))
        raise ResultFileError(f"{found[0]}: row {rows[k]}: conditioning = {index[k]:.4g}, "
                              "expected a local conditioning index in [0, 1]")
    try:
        check_scene_points(pts, str(found[0]), rows)
    except ViewerError as exc:
        raise ResultFileError(str(exc)) from None
    top = float(index.max()) if len(index) else 1.0
    return pts, colormaps["viridis"](index / (top or 1.0))[:, :3]
