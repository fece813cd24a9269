"""What a mesh file says against what the reader made of it: the checks a part's mesh passes
before it is painted, so that a malformed file is refused in one line, or repaired and said so,
never turned silently into another part.

- **OBJ** indices are 1-based; a negative one counts back from the elements read so far (the
  OBJ rule), which trimesh resolves against the whole file instead: a file that interleaves
  vertices and faces with relative indices is rewritten to absolute indices first. An index of
  0 (a 0-based writer) or past the elements read so far is refused, naming the line.
- **PLY**: the header's element counts must match the data: an ASCII body with more or fewer
  lines than the header declares is refused (the reader would take the wrong lines as faces);
  a face index outside 0..V−1 is refused, naming the face.
- **STL**: an ASCII file reads as text (``solid`` first, no NUL byte); any other is binary,
  whose size must be its 84-byte header and 50 bytes for each triangle the header counts: a
  count that does not match (a truncated copy, a damaged header, another format named .stl) is
  refused, saying both, not read as an ASCII file with no triangles. An ASCII file's facets
  must hold three vertices of three numbers each, every ``facet`` closed by ``endfacet``: the
  first that does not is refused, naming its line (the reader said "cannot reshape array").
- **Faces**: a face that repeats another (the same three corners in the same turning order) is
  dropped and counted: painting it twice would double its film and area. The same corners in
  the opposite order are the two sides of a sheet and both stay.
"""
from __future__ import annotations

import re

import numpy as np

from ..errors import MeshFileError

OBJ_ELEMENTS = {b"v": 0, b"vt": 1, b"vn": 2}  # an f index's slots: vertex/texture/normal






def _obj_index(token: bytes, seen: int, source: str, line: int) -> int:
    """The absolute 1-based vertex index of one OBJ face corner, ``seen`` vertices before."""
    try:
        k = int(token)
    except ValueError:
        raise MeshFileError(f"{source}: line {line}: face index {token.decode('latin-1')!r} "
                            "is not an integer") from None
    if k == 0:
        raise MeshFileError(f"{source}: line {line}: face index 0 (OBJ indices start at 1; "
                            "was the file written 0-based?)")
    absolute = seen + 1 + k if k < 0 else k
    if not 1 <= absolute <= seen:
        raise MeshFileError(f"{source}: line {line}: face index {k} refers to vertex "
                            f"{absolute}, but {seen} vertices are defined before it")
    return absolute


def _relative(token: bytes, seen: int) -> bytes:
    """A texture or normal slot: a relative index made absolute where it can be (the part
    does not use them, so the reader's own rules judge the rest)."""
    if token.startswith(b"-") and token[1:].isdigit() and int(token) + seen >= 0:
        return b"%d" % (seen + 1 + int(token))
    return token


def obj_absolute(data: bytes, source: str) -> bytes:
    """``data`` with every face index absolute and checked (see the module's rules); the
    same bytes when no index is relative."""
    lines = data.split(b"\n")
    seen = [0, 0, 0]
    relative = False
    out = []
    for number, raw in enumerate(lines, 1):
        words = raw.split(b"#", 1)[0].split()
        if words and words[0] in OBJ_ELEMENTS:
            seen[OBJ_ELEMENTS[words[0]]] += 1
        elif words and words[0] in (b"f", b"l", b"p"):
            corners = []
            for corner in words[1:]:
                slots = corner.split(b"/")
                relative |= any(t.startswith(b"-") for t in slots)
                slots[0] = b"%d" % _obj_index(slots[0], seen[0], source, number)
                slots[1:3] = [_relative(t, seen[i + 1]) for i, t in enumerate(slots[1:3])]
                corners.append(b"/".join(slots))
            raw = words[0] + b" " + b" ".join(corners)
        out.append(raw)
    return b"\n".join(out) if relative else data


def _ply_header(data: bytes, source: str):
    """(format, [(element, count)], body offset) of a PLY file's header."""
    end = data.find(b"end_header")
    if not data.startswith(b"ply") or end < 0:
        raise MeshFileError(f"{source}: not a PLY file (no 'ply' … 'end_header' header)")
    body = data.find(b"\n", end)
    body = len(data) if body < 0 else body + 1
    fmt, elements = None, []
    for raw in data[:end].decode("latin-1").splitlines():
        words = raw.split()
        if len(words) >= 2 and words[0] == "format":
            fmt = words[1]
        elif len(words) == 3 and words[0] == "element":
            try:
                count = int(words[2])
            except ValueError:
                raise MeshFileError(f"{source}: PLY header: element {words[1]} count "
                                    f"{words[2]!r} is not an integer") from None
            if count < 0:
                raise MeshFileError(f"{source}: PLY header: element {words[1]} count {count} "
                                    "is negative")
            elements.append((words[1], count))
    return fmt, elements, body


def ply_counts(data: bytes, source: str) -> dict[str, int]:
    """{element: count} of a PLY header, checked against an ASCII body's lines."""
    fmt, elements, body = _ply_header(data, source)
    counts = dict(elements)
    if fmt == "ascii":
        lines = sum(1 for raw in data[body:].splitlines() if raw.strip())
        declared = sum(c for _, c in elements)
        if lines != declared:
            said = " and ".join(f"{c} {e}" for e, c in elements)
            raise MeshFileError(f"{source}: the PLY header declares {said} ({declared} lines) "
                                f"but the data has {lines} lines")
    return counts


STL_HEADER, STL_TRIANGLE = 84, 50  # bytes: a binary STL's header (with its count), a triangle


def stl_count(data: bytes, source: str) -> int | None:
    """A binary STL's triangle count, checked against the file's size (None: an ASCII STL,
    ``solid`` first and no NUL byte)."""
    if data.lstrip()[:5].lower() == b"solid" and b"\0" not in data:
        return None
    if len(data) < STL_HEADER:
        raise MeshFileError(f"{source}: {len(data)} bytes: not an ASCII STL (solid … endsolid), "
                            f"and shorter than a binary STL's {STL_HEADER}-byte header")
    count = int.from_bytes(data[80:STL_HEADER], "little")
    size = STL_HEADER + STL_TRIANGLE * count
    if len(data) != size:
        held = (len(data) - STL_HEADER) / STL_TRIANGLE
        raise MeshFileError(f"{source}: a binary STL whose header counts {count} triangles "
                            f"({size} bytes), but the file has {len(data)} bytes ({held:.6g} "
                            "triangles): truncated, damaged, or another format")
    return count


_NUMBER = rb"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|[-+]?(?:nan|inf(?:inity)?)"
_STL_WORD = re.compile(rb"^[ \t]*(facet|vertex|endfacet)\b", re.M | re.I)
_STL_INITIAL = re.compile(rb"^[ \t]*(f|v|e)(?:acet|ertex|ndfacet)\b", re.M | re.I)
_STL_VERTEX = re.compile(rb"^[ \t]*vertex[ \t]+(?:(?:%s)[ \t]+){2}(?:%s)[ \t]*\r?$"
                         % (_NUMBER, _NUMBER), re.M | re.I)


def stl_ascii(data: bytes, source: str) -> int:
    """An ASCII STL's facet count, its structure checked: each ``facet`` … ``endfacet`` holds
    three ``vertex x y z`` lines of three numbers, and no vertex stands outside a facet."""
    # the keywords' initials in file order: a sound file's are "fvvve" per facet
    initials = b"".join(_STL_INITIAL.findall(data)).lower()
    facets = len(initials) // 5
    if initials == b"fvvve" * facets and len(_STL_VERTEX.findall(data)) == 3 * facets:
        return facets
    # something is wrong: find the first place, in file order (only on failure)
    found = list(_STL_WORD.finditer(data))
    kind = [b"fve".index(m[1][:1].lower()) for m in found]  # 0 facet, 1 vertex, 2 endfacet

    def line(i: int) -> int:
        return data.count(b"\n", 0, found[i].start()) + 1

    start, corners = None, 0
    for i, m in enumerate(found):
        if kind[i] == 1:
            end = data.find(b"\n", m.start())
            text = data[m.start():end if end >= 0 else len(data)].rstrip(b"\r")
            if not _STL_VERTEX.fullmatch(text):
                shown = text.strip().decode("latin-1")[:60]
                raise MeshFileError(f"{source}: line {line(i)}: {shown!r}: an ASCII STL vertex "
                                    "is 'vertex x y z', three numbers")
            if start is None:
                raise MeshFileError(f"{source}: line {line(i)}: an ASCII STL vertex outside "
                                    "any facet … endfacet")
            corners += 1
        elif kind[i] == 0:
            if start is not None:
                raise MeshFileError(f"{source}: line {line(start)}: an ASCII STL facet with no "
                                    "endfacet before the next facet")
            start, corners = i, 0
        else:
            if start is None:
                raise MeshFileError(f"{source}: line {line(i)}: an ASCII STL endfacet with no "
                                    "facet before it")
            if corners != 3:
                raise MeshFileError(f"{source}: line {line(start)}: an ASCII STL facet with "
                                    f"{corners} vertices (a triangle has 3)")
            start = None
    if start is None:  # nothing found wrong after all: the reader judges
        return facets
    raise MeshFileError(f"{source}: line {line(start)}: an ASCII STL facet with no endfacet "
                        "(a truncated file?)")


def check_indices(vertices: np.ndarray, faces: np.ndarray, source: str) -> None:
    """Refuse a face index outside 0..V−1, naming the first such face."""
    f = np.asarray(faces)
    bad = (f < 0) | (f >= len(vertices))
    if bad.any():
        k = int(np.argmax(bad.any(axis=1)))
        raise MeshFileError(f"{source}: face {k} has vertex index "
                            f"{int(f[k][bad[k]][0])}, outside 0..{len(vertices) - 1}")


def unique_faces(faces: np.ndarray) -> tuple[np.ndarray, int]:
    """(faces without repeats, how many were dropped): a repeat has the same three corners in
    the same cyclic order; the first of each is kept, in file order."""
    f = np.asarray(faces)
    if len(f) == 0:
        return f, 0
    first = np.argmin(f, axis=1)  # rotate each triangle to start at its least corner
    rows = np.arange(len(f))[:, None]
    canonical = f[rows, (first[:, None] + np.arange(3)) % 3]
    _, keep = np.unique(canonical, axis=0, return_index=True)
    keep.sort()
    return f[keep], len(f) - len(keep)


__all__ = ["STL_HEADER", "STL_TRIANGLE", "check_indices", "obj_absolute", "ply_counts",
           "stl_ascii", "stl_count", "unique_faces"]
