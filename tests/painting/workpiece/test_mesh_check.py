"""Mesh files that contradict themselves: refused in one line, or repaired to the part the
file describes (areas against hand-computed triangles)."""
import io

import numpy as np
import pytest
import trimesh

from pollard_pin.painting.errors import MeshFileError
from pollard_pin.painting.workpiece.mesh_check import (
    check_indices,
    obj_absolute,
    ply_counts,
    stl_ascii,
    stl_count,
    unique_faces,
)

# two unit right triangles, far apart, each written with indices relative to its own vertices
INTERLEAVED = b"""v 0 0 0
v 1 0 0
v 0 1 0
f -3 -2 -1
v 5 0 0
v 5 2 0
v 5 0 2
f -3 -2 -1
"""


def _areas(data: bytes) -> np.ndarray:
    m = trimesh.load(io.BytesIO(data), file_type="obj", force="mesh", process=False)
    return np.sort(m.area_faces)


def test_relative_obj_indices_count_back_from_the_line():
    fixed = obj_absolute(INTERLEAVED, "t.obj")
    assert b"f 1 2 3" in fixed and b"f 4 5 6" in fixed
    # the file's two triangles: areas 1/2 and 2 (by hand), total 2.5
    assert np.allclose(_areas(fixed), [0.5, 2.0], rtol=0, atol=1e-14)
    # the reader alone resolves them against the whole file: another part (so the check bites)
    assert not np.allclose(_areas(INTERLEAVED), [0.5, 2.0])


def test_absolute_obj_is_left_as_is():
    data = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1 # a comment\n"
    assert obj_absolute(data, "t.obj") is data
    relative = data.replace(b"f 1//1 2//1 3//1", b"f -3//-1 -2//-1 -1//-1")
    assert b"f 1//1 2//1 3//1" in obj_absolute(relative, "t.obj")


@pytest.mark.parametrize("face, words", [
    (b"f 0 1 2", ["line 4", "index 0", "0-based"]),
    (b"f 1 2 4", ["line 4", "vertex 4", "3 vertices"]),
    (b"f 1 2 -4", ["line 4", "index -4", "vertex 0"]),
    (b"f 1 2 x", ["line 4", "'x'"]),
])
def test_bad_obj_indices_name_the_line(face, words):
    data = b"v 0 0 0\nv 1 0 0\nv 0 1 0\n" + face + b"\n"
    with pytest.raises(MeshFileError) as exc:
        obj_absolute(data, "t.obj")
    text = str(exc.value)
    assert "\n" not in text and all(w in text for w in words), text


PLY = (b"ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
       b"property float z\nelement face 2\nproperty list uchar int vertex_indices\n"
       b"end_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n")


def test_ply_counts_match_the_body():
    assert ply_counts(PLY, "t.ply") == {"vertex": 4, "face": 2}
    short = PLY.replace(b"element vertex 4", b"element vertex 3")
    with pytest.raises(MeshFileError, match=r"3 vertex and 2 face \(5 lines\) but the data "
                                            r"has 6 lines"):
        ply_counts(short, "t.ply")
    with pytest.raises(MeshFileError, match="not a PLY"):
        ply_counts(b"solid x\nendsolid\n", "t.ply")


def test_negative_ply_index_is_refused():
    bad = PLY.replace(b"3 0 2 3\n", b"3 0 2 -1\n")
    m = trimesh.load(io.BytesIO(bad), file_type="ply", force="mesh", process=False)
    with pytest.raises(MeshFileError, match=r"face 1 has vertex index -1, outside 0\.\.3"):
        check_indices(m.vertices, m.faces, "t.ply")
    check_indices(np.zeros((4, 3)), np.array([[0, 1, 2], [0, 2, 3]]), "t.ply")  # in range


def test_repeated_faces_dropped_the_two_sides_of_a_sheet_kept():
    f = np.array([[0, 1, 2], [1, 2, 0], [2, 0, 1], [0, 2, 1], [0, 2, 3], [0, 1, 2]])
    kept, dropped = unique_faces(f)
    # [1 2 0], [2 0 1], [0 1 2] repeat the first; [0 2 1] is its other side
    assert dropped == 3 and kept.tolist() == [[0, 1, 2], [0, 2, 1], [0, 2, 3]]


# --- through the part loader (painting.workpiece.mesh.load_part) ---------------------------
def _load(tmp_path, name, data: bytes, **kwargs):
    from pollard_pin.painting.workpiece.mesh import load_part

    (tmp_path / name).write_bytes(data)
    return load_part(tmp_path / name, **kwargs)


def test_loader_reads_relative_obj_indices_as_the_file_means(tmp_path):
    """The two triangles of INTERLEAVED: areas 1/2 and 2 by hand (the reader alone made
    another part)."""
    part = _load(tmp_path, "t.obj", INTERLEAVED, facing=(0, 0, 1))
    assert np.allclose(np.sort(part.areas), [0.5, 2.0], rtol=0, atol=1e-14)


def _binary_stl(triangles: list, header: bytes = b"binary") -> bytes:
    """A binary STL of ``triangles`` (3 corners each), written by hand: an 80-byte header, the
    count, then per triangle a zero normal, the corners as float32 and two attribute bytes."""
    body = b"".join(np.zeros(3, "<f4").tobytes() + np.asarray(t, "<f4").tobytes() + b"\0\0"
                    for t in triangles)
    return header.ljust(80, b" ") + len(triangles).to_bytes(4, "little") + body


SQUARE = [[[0, 0, 0], [1, 0, 0], [1, 1, 0]], [[0, 0, 0], [1, 1, 0], [0, 1, 0]]]
GOOD_STL = _binary_stl(SQUARE)


def test_a_binary_stl_count_is_checked_against_its_size():
    assert len(GOOD_STL) == 84 + 2 * 50 and stl_count(GOOD_STL, "t.stl") == 2
    # a header that begins "solid" (some writers'), and an ASCII file: read as they are
    assert stl_count(_binary_stl(SQUARE, b"solid square"), "t.stl") == 2
    assert stl_count(b"solid s\nfacet normal 0 0 1\nendsolid s\n", "t.stl") is None


def _count(data: bytes, count: int) -> bytes:
    return data[:80] + count.to_bytes(4, "little") + data[84:]


@pytest.mark.parametrize("data, says", [
    (_count(GOOD_STL, 3), "header counts 3 triangles (234 bytes), but the file has 184 bytes "
                          "(2 triangles): truncated"),
    (_count(GOOD_STL, 1), "header counts 1 triangles (134 bytes), but the file has 184 bytes"),
    (_count(GOOD_STL, 2**32 - 1), "header counts 4294967295 triangles"),
    (GOOD_STL[:150], "the file has 150 bytes (1.32 triangles)"),
    (_count(_binary_stl(SQUARE, b"solid square"), 7), "header counts 7 triangles"),
    (b"\x89PNG\r\n\x1a\n" + bytes(range(256)), "truncated, damaged, or another format"),
    (GOOD_STL[:60], "60 bytes: not an ASCII STL (solid … endsolid), and shorter than a binary "
                    "STL's 84-byte header"),
])
def test_a_binary_stl_that_lies_about_its_count_is_refused(tmp_path, data, says):
    # the old loader read each as an ASCII STL: "no triangles in the file"
    with pytest.raises(MeshFileError) as exc:
        _load(tmp_path, "lie.stl", data, facing=(0, 0, 1))
    msg = str(exc.value)
    assert says in msg and "\n" not in msg and len(msg) <= 250, msg


def _ascii_stl(*facets: str) -> bytes:
    return ("solid s\n" + "".join(f"facet normal 0 0 1\nouter loop\n{f}endloop\nendfacet\n"
                                   for f in facets) + "endsolid s\n").encode()


TRIANGLE = "vertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\n"


@pytest.mark.parametrize("data, says", [
    (_ascii_stl(TRIANGLE, "vertex 0 0 0\nvertex 1 0 0\n"),
     "line 9: an ASCII STL facet with 2 vertices (a triangle has 3)"),
    (_ascii_stl(TRIANGLE + "vertex 0 1 0\n"), "line 2: an ASCII STL facet with 4 vertices (a "
                                                  "triangle has 3)"),
    (_ascii_stl(TRIANGLE.replace("1 1 0", "1 1 zz")),
     "line 6: 'vertex 1 1 zz': an ASCII STL vertex is 'vertex x y z', three numbers"),
    (_ascii_stl(TRIANGLE).replace(b"endfacet\n", b""), "line 2: an ASCII STL facet with no "
                                                        "endfacet (a truncated file?)"),
    (_ascii_stl(TRIANGLE, TRIANGLE).replace(b"endfacet\n", b"", 1),
     "line 2: an ASCII STL facet with no endfacet before the next facet"),
    (b"solid s\nvertex 0 0 0\n" + _ascii_stl(TRIANGLE)[8:],
     "line 2: an ASCII STL vertex outside any facet … endfacet"),
    (b"solid s\nendfacet\n" + _ascii_stl(TRIANGLE)[8:],
     "line 2: an ASCII STL endfacet with no facet before it"),
])
def test_an_ascii_stl_facet_not_a_triangle_is_refused_naming_its_line(tmp_path, data, says):
    """Line numbers counted by hand in the files above; the reader alone said "cannot reshape
    array of size 6 into shape (3)" or read no triangles."""
    with pytest.raises(MeshFileError) as exc:
        stl_ascii(data, "t.stl")
    assert str(exc.value) == f"t.stl: {says}"


def test_a_sound_ascii_stl_is_read_as_written(tmp_path):
    """CRLF ends, indentation, upper-case keywords and exponents pass the check; the loader's
    two triangles are the file's (areas 1/2 each, by hand)."""
    data = _ascii_stl(TRIANGLE, "  VERTEX 0 0 0\n  vertex 1e0 1 0\n  vertex 0 +1.0 -0\n")
    assert stl_ascii(data, "t.stl") == 2
    part = _load(tmp_path, "t.stl", data.replace(b"\n", b"\r\n"), facing=(0, 0, 1))
    assert np.allclose(part.areas, [0.5, 0.5], rtol=0, atol=1e-14)


def test_loader_reads_a_binary_stl_written_by_hand(tmp_path):
    part = _load(tmp_path, "square.stl", GOOD_STL, facing=(0, 0, 1))
    assert len(part.faces) == 2 and abs(part.areas.sum() - 1.0) < 1e-14


@pytest.mark.parametrize("name, data, says", [
    ("zero.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "line 4: face index 0"),
    ("short.ply", PLY.replace(b"element vertex 4", b"element vertex 3"),
     "but the data has 6 lines"),
    ("negative.ply", PLY.replace(b"3 0 2 3\n", b"3 0 2 -1\n"),
     "face 1 has vertex index -1, outside 0..3"),
])
def test_loader_refuses_a_self_contradicting_file_in_one_line(tmp_path, name, data, says):
    from pollard_pin.painting.errors import MeshError

    with pytest.raises(MeshError) as exc:
        _load(tmp_path, name, data, facing=(0, 0, 1))
    msg = str(exc.value)
    assert says in msg and "\n" not in msg and len(msg) <= 250, msg


def test_loader_drops_repeated_and_zero_area_faces_and_says_so(tmp_path):
    """PLY's square (two triangles, area 1) with each face written three times (rotated
    corners) and one face of zero area: the part is the square, with two notes."""
    body = b"3 0 1 2\n3 0 2 3\n3 1 2 0\n3 2 3 0\n3 2 0 1\n3 3 0 2\n3 0 1 1\n"
    data = PLY.replace(b"element face 2", b"element face 7").split(b"end_header\n")[0]
    data += b"end_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n" + body
    with pytest.warns(UserWarning) as notes:
        part = _load(tmp_path, "rep.ply", data, facing=(0, 0, 1))
    said = [str(w.message) for w in notes]
    assert any("dropped 4 repeated faces" in s for s in said), said
    assert any("dropped 1 faces of zero area" in s for s in said), said
    assert len(part.faces) == 2 and abs(part.areas.sum() - 1.0) < 1e-14
