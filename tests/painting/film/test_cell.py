"""The cell's film (paint/film/cell.py, docs/model.md §26.3): with the trigger open
throughout it is the spray model's film; split into two runs at a shared sample, the two
films add up to the one."""
import numpy as np

from pollard_pin.painting.film.cell import run_weights, weighted_film
from pollard_pin.painting.spray.deposition import Gun, film

GUN = Gun(0.15, 0.01, 1.5e-7)


def stroke(n: int = 400):
    t = np.linspace(0.0, 1.0, n)
    p = np.column_stack([np.full(n, 0.55), -0.15 + 0.3 * t, np.full(n, 0.1)])
    a = np.tile([1.0, 0.0, 0.0], (n, 1))
    y, z = np.meshgrid(np.linspace(-0.1, 0.1, 41), np.linspace(0.08, 0.12, 5))
    s = np.column_stack([np.full(y.size, 0.70), y.ravel(), z.ravel()])
    return t, p, a, s


def test_open_throughout_it_is_the_spray_models_film():
    t, p, a, s = stroke()
    n = np.array([-1.0, 0.0, 0.0])
    ours = weighted_film(GUN, t, p, a, np.ones(len(t)), s, n, s.mean(0)).thickness
    theirs = film(GUN, t, p, a, s, n, origin=s.mean(0)).thickness
    assert np.abs(ours - theirs).max() <= 1e-12 * theirs.max()  # seen 0.0


def test_two_runs_sharing_a_sample_add_up_to_one():
    t, p, a, s = stroke()
    n = np.array([-1.0, 0.0, 0.0])
    k = 211
    first, second = np.zeros(len(t)), np.zeros(len(t))
    first[:k + 1], second[k:] = 1.0, 1.0
    whole = weighted_film(GUN, t, p, a, np.ones(len(t)), s, n, s.mean(0)).thickness
    parts = sum(weighted_film(GUN, t, p, a, x, s, n, s.mean(0)).thickness
                for x in (first, second))
    assert np.abs(parts - whole).max() <= 1e-14 * whole.max()  # seen 2e-16
    w, _ = run_weights(t, first)
    assert w[k] == 0.5 * (t[k] - t[k - 1]) and w[k + 1] == 0.0
