"""film.ply (io/ply.py): a binary PLY that trimesh reads back with its thickness and colours."""
import numpy as np
import pytest
import trimesh

from pollard_pin.io.ply import write_film_ply


def test_ply_round_trip(tmp_path):
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float) * 0.1
    f = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    th = np.array([1e-6, 2e-6, 3e-6, 4.5e-6])
    rgba = np.array([[255, 0, 0, 255], [0, 255, 0, 255], [0, 0, 255, 255], [1, 2, 3, 255]],
                    dtype=np.uint8)
    path = tmp_path / "film.ply"
    write_film_ply(path, v, f, th, rgba)
    head = path.read_bytes()[:400]
    assert head.startswith(b"ply\nformat binary_little_endian 1.0\n")
    assert b"property double thickness" in head and b"property uchar red" in head
    back = trimesh.load(path, process=False)
    assert np.array_equal(back.faces, f)
    assert np.abs(back.vertices - v).max() < 1e-8  # float32 positions
    raw = back.metadata["_ply_raw"]["vertex"]["data"]
    assert np.array_equal(raw["thickness"], th)  # float64: exact
    assert np.array_equal(back.visual.vertex_colors, rgba)
    assert not list(tmp_path.glob("*.tmp*"))


def test_read_film_ply(tmp_path):
    from pollard_pin.io.ply import read_film_ply
    from pollard_pin.io.table import ResultFileError

    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype=float)
    write_film_ply(tmp_path / "f.ply", v, [[0, 1, 2]], [1e-6, 2e-6, 3e-6],
                   np.full((3, 4), 255, dtype=np.uint8))
    vv, ff, th = read_film_ply(tmp_path / "f.ply")
    assert np.array_equal(th, [1e-6, 2e-6, 3e-6]) and ff.tolist() == [[0, 1, 2]]
    (tmp_path / "g.ply").write_bytes(b"not a ply at all")
    with pytest.raises(ResultFileError, match="not a film PLY"):
        read_film_ply(tmp_path / "g.ply")


def _film(tmp_path, faces=((0, 1, 2), (1, 3, 2)), th=(1e-6, 2e-6, 3e-6, 4e-6)):
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]], dtype=float) * 0.1
    path = tmp_path / "film.ply"
    write_film_ply(path, v, np.array(faces), np.array(th, float),
                   np.full((4, 4), 255, dtype=np.uint8))
    return path


@pytest.mark.parametrize("faces, th, target, words", [
    (((0, 1, 2), (1, 3, 1592)), None, None,
     "face 1 (from 0): vertex index 1592, outside 0 … 3 (the file's 4 vertices)"),
    (((0, -7, 2), (1, 3, 2)), None, None, "face 0 (from 0): vertex index -7, outside 0 … 3"),
    (None, (1e-6, -2e-6, 3e-6, 4e-6), None, "vertex 1 (from 0): thickness = -2e-06 m, below 0"),
    (None, (1e-6, 2e-6, float("nan"), 4e-6), None, "vertex 2 (from 0): thickness not finite (nan)"),
    (None, (1e-6, 2e-6, 3e-6, 25e-6 * 1e30), 25e-6,
     "vertex 3 (from 0): thickness = 2.5e+25 m, over 1000 × the target 2.5e-05 m"),
])
def test_read_film_ply_names_the_bad_element(tmp_path, faces, th, target, words):
    """Out-of-range face indices (which numpy would wrap, or index past the vertices) and
    films no spray lays are one line naming the file, the element and the value."""
    from pollard_pin.io.ply import read_film_ply
    from pollard_pin.io.table import ResultFileError

    kw = {k: v for k, v in (("faces", faces), ("th", th)) if v is not None}
    path = _film(tmp_path, **kw)
    with pytest.raises(ResultFileError) as exc:
        read_film_ply(path, target)
    msg = str(exc.value)
    assert msg.startswith(f"{path}: ") and words in msg and "\n" not in msg, msg


def test_read_film_ply_takes_films_up_to_the_absurd_bound(tmp_path):
    from pollard_pin.io.ply import ABSURD_FILM, read_film_ply

    th = (0.0, 2e-6, 3e-6, 25e-6 * ABSURD_FILM)  # 0 (a shadow) and the bound itself are films
    _, f, back = read_film_ply(_film(tmp_path, th=th), 25e-6)
    assert np.array_equal(back, th) and f.tolist() == [[0, 1, 2], [1, 3, 2]]
