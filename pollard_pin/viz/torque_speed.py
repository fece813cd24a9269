"""The torque–speed figure of ``pollard-pin size`` (motor points against the rating
envelopes), and its sizing as a Markdown table and JSON (docs/model.md §19; the numbers:
:mod:`pollard_pin.dynamics.sizing`)."""
from __future__ import annotations

from pathlib import Path

from ..dynamics.sizing import CHECKS, Sizing
from ..io.json_text import finite_json

RATING = {"peak_torque": "peak", "rms_torque": "continuous", "speed": "max speed"}


def to_json(rep: dict) -> str:
    return finite_json(rep, "the torque-speed report", indent=2, ensure_ascii=False)


def _table(rep: dict, prefix: str) -> list[str]:
    head = " | ".join(f"{h} [{u}] | ÷ {RATING[r]}" for _, _, r, h, u in CHECKS)
    lines = ["| actuator | N | " + head.replace("|τm|", "\\|τm\\|").replace("|ωm|", "\\|ωm\\|")
             + " |", "|---|---:|" + "---:|" * (2 * len(CHECKS))]
    for n, row in rep["actuators"].items():
        cells = [f"{row[prefix + k]:.4g} | {row[prefix + k + '_ratio']:.3f}"
                 for k, _, _, _, _ in CHECKS]
        lines.append(f"| `{n}` | {row['gear_ratio']:g} | " + " | ".join(cells) + " |")
    return lines


def to_markdown(rep: dict) -> str:
    tr = rep["trajectory"]
    ub = rep["uniform_binding"]
    verdict = "within every rating" if rep["given_within_ratings"] else "**over a rating**"
    lines = [f"# Motor and gearbox sizing: {tr['name']} trajectory", "",
             f"{tr['samples']} samples over {tr['duration']:.4g} s; actuators from "
             f"{rep['actuator_file']}. Motor side: τm = τ/N + Jm·N·q̈ + b·N·q̇ + c·sign(q̇) "
             "(±c at rest), ωm = N·q̇ (docs/model.md §19).", "",
             f"## Given trajectory: {verdict}", "", *_table(rep, ""), "",
             "## Fastest cycle along the same path", "",
             f"* uniform time scaling: **{rep['uniform_min_duration']:.4g} s** (every limit "
             f"holds at this duration and any longer; binding: `{ub['actuator']}` "
             f"{ub['limit']}; each limit alone: "
             + ", ".join(f"{k.replace('_', ' ')} {v:.4g} s"
                         for k, v in rep["uniform_min_duration_by_limit"].items()) + ")"
             + ("; it changes the painting speed, so the film" if "time_optimal_film" in rep
                else ""),
             ]
    if rep["time_optimal_duration"] is None:
        lines += [f"* time-optimal (TOPP-RA): **failed**: {rep['time_optimal_error']}"]
        return "\n".join(lines) + "\n"
    between = rep["time_optimal_between_samples"]
    if rep.get("time_optimal_film"):
        lines += [f"* time-optimal, {rep['time_optimal_film']['summary']}"]
    lines += [f"* time-optimal (TOPP-RA, peak torque and speed, "
              f"{rep['time_optimal_start_end']}): "
              f"**{rep['time_optimal_duration']:.4g} s**; between the samples (s̈ constant "
              f"per interval, {between['check_points_per_interval']} check points per "
              f"interval and halfway between them, {between['intervals_tightened']} "
              f"intervals' ratings tightened) the worst use of a peak torque or speed is "
              f"{between['worst_utilisation']:.5f} (at s = {between['at_s']:.4g})", "",
              *_table(rep, "time_optimal_"),
              "", "Where the time-optimal cycle spends its time (binding limit, share of the "
              "duration):", ""]
    for label, share in rep["time_optimal_binding_shares"].items():
        what = ("switching between limits (no limit within 2 %)" if label == "switching"
                else f"`{label.split()[0]}` {label.split()[1].replace('_', ' ')}")
        lines.append(f"* {what}: {100 * share:.1f} %")
    lines += ["", "RMS = sqrt(∫τm² dt / T), trapezoid rule over the samples. The time-optimal "
              "cycle ignores the RMS limit; its ratio says whether the motor can repeat it "
              "without overheating."]
    return "\n".join(lines) + "\n"


def torque_speed_figure(sizing: Sizing):
    """Each motor's operating points (ωm, τm) for the given and the time-optimal trajectory,
    with its rating envelope: |τm| ≤ peak and |ωm| ≤ max speed (solid), ±continuous
    (dashed). Line gids: ``given_<actuator>``, ``time_optimal_<actuator>``,
    ``envelope_<actuator>``."""
    from .plots import figure_maker

    plt = figure_maker()
    act = sizing.actuators
    fig, axes = plt.subplots(2, 3, figsize=(13, 7.5), constrained_layout=True)
    for j, (ax, name) in enumerate(zip(axes.ravel(), act.names)):
        u = act.units[j]
        w, p, c = u.max_speed, u.peak_torque, u.continuous_torque
        (env,) = ax.plot([-w, w, w, -w, -w], [-p, -p, p, p, -p], color="k", lw=1.2,
                         label="peak, max speed")
        env.set_gid(f"envelope_{name}")
        for sign in (1, -1):
            ax.axhline(sign * c, color="k", lw=0.8, ls="--",
                       label="continuous (RMS)" if sign > 0 else None)
        for load, label, colour in ((sizing.given, "given", "tab:blue"),
                                    (sizing.optimal, "time_optimal", "tab:orange")):
            if load is None:  # no time-optimal traversal
                continue
            (ln,) = ax.plot(load.speed[:, j], load.torque[:, j], ".", ms=2, color=colour,
                            label=f"{label.replace('_', '-')} "
                                  f"({load.t[-1] - load.t[0]:.3g} s)")
            ln.set_gid(f"{label}_{name}")
        ax.set_title(f"{name} (N = {u.gear_ratio:g})", fontsize=10)
        ax.set_xlabel("motor speed ωm [rad/s]")
        ax.set_ylabel("motor torque τm [N·m]")
        ax.grid(True, alpha=0.3)
    handles, labels = axes.ravel()[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=4, markerscale=4,
               fontsize=9)
    fig.suptitle(f"Motor operating points, {sizing.report['trajectory']['name']} trajectory")
    return fig


def write_torque_speed(sizing: Sizing, out_dir, dpi: int = 100) -> Path:
    """Write :func:`torque_speed_figure` as ``out_dir/torque_speed.png``."""
    from ..io.atomic import make_folder
    from .plots import save_png

    return save_png(torque_speed_figure(sizing), make_folder(out_dir) / "torque_speed.png", dpi)


__all__ = ["to_json", "to_markdown", "torque_speed_figure", "write_torque_speed"]
