"""The front's figure (viz/design.py): one marker set per robot count, the baseline, the
chosen design, every evaluation faint."""
from pollard_pin.viz.design import front_figure, write_front_png

FRONT = [{"parts_per_hour": 120.0, "robots": 1, "motor_use": 0.8, "kmin": 2e4,
          "moving_mass": 6.0},
         {"parts_per_hour": 200.0, "robots": 2, "motor_use": 0.5, "kmin": 3e4,
          "moving_mass": 9.0}]
OTHERS = [{"parts_per_hour": 90.0, "robots": 2, "motor_use": 0.9, "kmin": 1e4,
           "moving_mass": 9.5}]
BASE = {"parts_per_hour": 150.0, "robots": 2, "motor_use": 0.6, "kmin": 2.5e4,
        "moving_mass": 8.0}


def _gids(fig):
    return {a.get_gid() for ax in fig.axes for a in ax.collections}


def test_the_figure_draws_what_it_is_given():
    fig = front_figure(FRONT, OTHERS, BASE, chosen=0)
    assert len(fig.axes) == 2
    assert _gids(fig) == {"evaluations", "front_1", "front_2", "baseline", "chosen"}
    ax = fig.axes[0]  # moving mass against parts per hour
    chosen = next(c for c in ax.collections if c.get_gid() == "chosen")
    assert chosen.get_offsets().tolist() == [[6.0, 120.0]]
    assert _gids(front_figure(FRONT)) == {"front_1", "front_2"}  # no baseline: none drawn


def test_the_png_is_written(tmp_path):
    path = write_front_png(tmp_path / "front.png", FRONT, OTHERS, None, 1)
    assert path.read_bytes()[:4] == b"\x89PNG"
