"""MeshCat's static export, offline: the offline window keeps the scene tree as MeshCat's
server does (a later object replaces an earlier one, a delete drops a subtree), and the page
is self-contained and gives back the commands it was written with."""
import re

import numpy as np

from pollard_pin.viz.meshcat_page import OfflineWindow, page_commands, static_page


def _scene() -> OfflineWindow:
    """Two objects, a transform, a replaced object and a deleted subtree, sent through
    MeshCat's own command classes."""
    window = OfflineWindow()  # imports meshcat without its pyzmq deprecation warning
    import meshcat.geometry as g
    import meshcat.transformations as tf
    from meshcat.commands import Delete, SetObject, SetTransform
    from meshcat.path import Path

    red = g.MeshLambertMaterial(color=0xFF0000)
    window.send(SetObject(g.Sphere(0.5), red, Path(("a", "box"))))
    window.send(SetObject(g.Box([0.1, 0.2, 0.3]), red, Path(("a", "box"))))  # replaces
    window.send(SetTransform(tf.translation_matrix([1.0, 2.0, 3.0]), Path(("a", "box"))))
    window.send(SetObject(g.Sphere(0.1), red, Path(("b", "ball"))))
    window.send(Delete(Path(("b",))))
    return window


def test_offline_window_keeps_the_scene_tree_as_meshcat_server_does():
    cmds = page_commands(static_page(_scene().commands()))
    assert [(c["type"], c["path"]) for c in cmds] == [("set_object", "/a/box"),
                                                     ("set_transform", "/a/box")]
    (geometry,) = cmds[0]["object"]["geometries"]
    assert geometry["type"] == "BoxGeometry"
    assert (geometry["width"], geometry["height"], geometry["depth"]) == (0.1, 0.2, 0.3)
    matrix = np.array(cmds[1]["matrix"], dtype=float).reshape(4, 4).T  # column-major
    assert np.array_equal(matrix[:3, 3], [1.0, 2.0, 3.0])


def test_static_page_is_self_contained():
    html = static_page(_scene().commands(), title="t", legend="<p id='legend'></p>")
    assert "MeshCat.Viewer" in html and len(html) > 500_000  # the viewer bundle is inline
    assert not re.search(r"<script[^>]+src=", html), "page must not load external scripts"
    assert not re.search(r"https?://(?!www\.w3\.org)", html.split("var meshcat_commands")[1])
    assert "<p id='legend'></p>" in html and "<title>t</title>" in html
