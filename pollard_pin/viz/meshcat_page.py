"""MeshCat's static export, offline: :class:`OfflineWindow` records a scene's commands the
way MeshCat's server does, :func:`static_page` writes them as one self-contained HTML page
(MeshCat's viewer bundle inline) and :func:`page_commands` reads a page's commands back."""
from __future__ import annotations

import base64
from pathlib import Path


# --- an offline MeshCat "window": records commands exactly as MeshCat's server does ---------
class OfflineWindow:
    """Stand-in for ``meshcat.visualizer.ViewerWindow`` that needs no server.

    It keeps the scene tree the way ``meshcat.servers.zmqserver`` does (objects, properties,
    transforms, animation per path) and renders it with :meth:`get_scene`.
    """

    web_url = None
    zmq_url = None

    def __init__(self):
        import_meshcat()
        from meshcat.servers.tree import SceneTree

        self.tree = SceneTree()

    def send(self, command) -> None:
        import umsgpack
        from meshcat.servers.tree import SceneTree, find_node

        data = command.lower()
        cmd = data["type"]
        path = [p for p in data["path"].split("/") if p]
        blob = umsgpack.packb(data)
        node = find_node(self.tree, path)
        if cmd == "set_object":
            node.object, node.properties = blob, []
        elif cmd == "set_transform":
            node.transform = blob
        elif cmd == "set_property":
            node.properties.append(blob)
        elif cmd == "set_animation":
            node.animation = blob
        elif cmd == "delete":
            if path:
                parent = find_node(self.tree, path[:-1])
                parent.pop(path[-1], None)
            else:
                self.tree = SceneTree()
        else:  # pragma: no cover - meshcat has no other scene commands
            raise ValueError(f"unsupported meshcat command {cmd!r}")

    def commands(self) -> list[bytes]:
        """The msgpack command blobs in the order MeshCat's server replays them."""
        from meshcat.servers.tree import walk

        out = []
        for node in walk(self.tree):
            if node.object is not None:
                out.append(node.object)
            out += node.properties
            if node.transform is not None:
                out.append(node.transform)
            if node.animation is not None:
                out.append(node.animation)
        return out

    def get_scene(self, title: str = "Pollard robot (MeshCat)", legend: str = "") -> str:
        return static_page(self.commands(), title, legend)

    def get_image(self):
        raise RuntimeError("an offline MeshCat scene has no browser to capture images from")

    def close(self):
        pass


def import_meshcat():
    """``import meshcat`` without its pyzmq deprecation warning (zmq.eventloop.ioloop)."""
    import warnings

    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", category=DeprecationWarning, module="meshcat")
        warnings.filterwarnings("ignore", message=".*zmq.eventloop.ioloop.*")
        import meshcat
        import meshcat.servers.zmqserver  # noqa: F401 - where the warning comes from
    return meshcat


def _viewer_bundle() -> str:
    meshcat = import_meshcat()

    return (Path(meshcat.__file__).parent / "viewer" / "dist" / "main.min.js").read_text()


def static_page(commands: list[bytes], title: str = "Pollard robot (MeshCat)",
                legend: str = "") -> str:
    """MeshCat's static export of a list of command blobs.

    Same layout as the page MeshCat's server returns for ``get_scene`` (viewer bundle inline,
    then the commands), except that the commands are decoded and applied synchronously, in
    order, rather than through one asynchronous ``fetch`` each, and that the page marks
    itself ready (``document.body.dataset.meshcatReady = "1"``) once all are applied;
    ``legend`` (HTML, e.g. a film's colour bar) is laid over the scene.
    """
    blobs = ",\n".join(f'"{base64.b64encode(c).decode()}"' for c in commands)
    return f"""<!DOCTYPE html>
<html>
<head><meta charset="utf-8"><title>{title}</title>
<style>
body {{ margin: 0; }}
#meshcat-pane {{ width: 100vw; height: 100vh; overflow: hidden; }}
</style>
</head>
<body>
<div id="meshcat-pane"></div>{legend}
<script>
{_viewer_bundle()}
</script>
<script>
var viewer = new MeshCat.Viewer(document.getElementById("meshcat-pane"));
var meshcat_commands = [
{blobs}
];
for (const b64 of meshcat_commands) {{
    const raw = atob(b64);
    const bytes = new Uint8Array(raw.length);
    for (let i = 0; i < raw.length; i++) bytes[i] = raw.charCodeAt(i);
    viewer.handle_command_bytearray(bytes);
}}
viewer.gui.open();
document.body.dataset.meshcatReady = "1";
</script>
</body>
</html>
"""


def page_commands(html: str) -> list[dict]:
    """The decoded MeshCat commands of a static page: ours (:func:`static_page`) or the one
    MeshCat's server returns for ``get_scene``."""
    import re

    import umsgpack

    blobs = re.findall(r'data:application/octet-binary;base64,([A-Za-z0-9+/=]+)', html)
    if not blobs:
        start = html.index("var meshcat_commands = [")
        body = html[start:html.index("];", start)]
        blobs = re.findall(r'"([A-Za-z0-9+/=]+)"', body)
    return [umsgpack.unpackb(base64.b64decode(b)) for b in blobs]


__all__ = ["OfflineWindow", "import_meshcat", "page_commands", "static_page"]
