"""film.ply (io/ply.py): a binary PLY that trimesh reads back with its thickness and colours."""
import numpy as np
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
    import pytest

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
