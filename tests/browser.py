"""Headless Chromium for checking and capturing the viewer pages (tests and docs).

Uses the Debian ``chromium`` package (``/usr/bin/chromium``) and the Chrome DevTools
protocol over a WebSocket (``tornado``, a MeshCat dependency): open a page, wait until a
JavaScript condition holds, evaluate expressions, take a PNG screenshot. Flags as the
machine notes prescribe: headless, no sandbox (root), no GPU (WebGL falls back to software),
no background networking, a fresh profile directory.
"""
from __future__ import annotations

import asyncio
import base64
import json
import os
import re
import shutil
import subprocess
import tempfile
import time
import urllib.request
from pathlib import Path

FLAGS = ("--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--hide-scrollbars", "--mute-audio")


class BrowserError(RuntimeError):
    pass


def find_chromium() -> str | None:
    """Path of a Chromium/Chrome executable, or None. ``POLLARD_CHROMIUM`` overrides."""
    env = os.environ.get("POLLARD_CHROMIUM")
    if env:
        return env if shutil.which(env) or Path(env).exists() else None
    for name in ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable"):
        path = shutil.which(name)
        if path:
            return path
    return None


class Page:
    """One headless Chromium with one page, driven over the DevTools protocol."""

    def __init__(self, width: int = 1200, height: int = 750, executable: str | None = None,
                 timeout: float = 30.0):
        self.executable = executable or find_chromium()
        if self.executable is None:
            raise BrowserError("no chromium executable found (Debian: apt-get install chromium)")
        self.width, self.height, self.timeout = width, height, timeout
        self._profile = tempfile.mkdtemp(prefix="pollard-chromium-")
        self._proc = None
        self._ws = None
        self._id = 0
        self._loop = asyncio.new_event_loop()

    # --- process -------------------------------------------------------------------------
    def __enter__(self) -> Page:
        self._proc = subprocess.Popen(
            [self.executable, *FLAGS, f"--user-data-dir={self._profile}",
             f"--window-size={self.width},{self.height}", "--remote-debugging-port=0",
             "about:blank"],
            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        port = self._devtools_port()
        deadline = time.monotonic() + self.timeout
        ws_url = None
        while ws_url is None:
            with urllib.request.urlopen(f"http://127.0.0.1:{port}/json/list", timeout=5) as r:
                pages = [t for t in json.load(r) if t.get("type") == "page"]
            if pages:
                ws_url = pages[0]["webSocketDebuggerUrl"]
            elif time.monotonic() > deadline:
                raise BrowserError("chromium opened no page")
            else:
                time.sleep(0.1)
        self._loop.run_until_complete(self._connect(ws_url))
        self.call("Page.enable")
        self.call("Runtime.enable")
        self.call("Emulation.setDeviceMetricsOverride", {
            "width": self.width, "height": self.height, "deviceScaleFactor": 1, "mobile": False})
        return self

    def _devtools_port(self) -> int:
        deadline = time.monotonic() + self.timeout
        seen = []
        while time.monotonic() < deadline:
            line = self._proc.stderr.readline()
            if not line:
                if self._proc.poll() is not None:
                    raise BrowserError(f"chromium exited ({self._proc.returncode}): "
                                       + "".join(seen[-10:]))
                continue
            seen.append(line)
            m = re.search(r"DevTools listening on ws://[^:]+:(\d+)/", line)
            if m:
                # Keep draining stderr so chromium never blocks on a full pipe.
                import threading

                threading.Thread(target=self._proc.stderr.read, daemon=True).start()
                return int(m.group(1))
        raise BrowserError("chromium did not report a DevTools port: " + "".join(seen[-10:]))

    def __exit__(self, *exc):
        try:
            if self._ws is not None:
                self._ws.close()
        finally:
            if self._proc is not None and self._proc.poll() is None:
                self._proc.terminate()
                try:
                    self._proc.wait(10)
                except subprocess.TimeoutExpired:
                    self._proc.kill()
                    self._proc.wait()
            self._loop.close()
            shutil.rmtree(self._profile, ignore_errors=True)

    # --- protocol ------------------------------------------------------------------------
    async def _connect(self, url):
        from tornado.websocket import websocket_connect

        self._ws = await websocket_connect(url, max_message_size=512 * 1024 * 1024)

    async def _call(self, method, params):
        self._id += 1
        mid = self._id
        await self._ws.write_message(json.dumps({"id": mid, "method": method,
                                                 "params": params or {}}))
        while True:
            msg = await asyncio.wait_for(self._ws.read_message(), self.timeout)
            if msg is None:
                raise BrowserError("DevTools connection closed")
            data = json.loads(msg)
            if data.get("id") == mid:
                if "error" in data:
                    raise BrowserError(f"{method}: {data['error']}")
                return data.get("result", {})

    def call(self, method: str, params: dict | None = None) -> dict:
        return self._loop.run_until_complete(self._call(method, params))

    def evaluate(self, expression: str):
        r = self.call("Runtime.evaluate", {"expression": expression, "returnByValue": True,
                                                "awaitPromise": True})
        if "exceptionDetails" in r:
            raise BrowserError(f"{expression!r}: {r['exceptionDetails'].get('text')} "
                               f"{r['exceptionDetails'].get('exception', {}).get('description')}")
        return r["result"].get("value")

    def open(self, url: str) -> None:
        if "://" not in url:
            url = Path(url).resolve().as_uri()
        self.call("Page.navigate", {"url": url})

    def wait_for(self, expression: str, timeout: float | None = None) -> None:
        deadline = time.monotonic() + (timeout or self.timeout)
        while True:
            try:
                if self.evaluate(expression):
                    return
            except BrowserError:
                pass
            if time.monotonic() > deadline:
                raise BrowserError(f"timed out waiting for {expression!r}")
            time.sleep(0.1)

    def screenshot(self, path: str | Path | None = None) -> bytes:
        png = base64.b64decode(self.call("Page.captureScreenshot", {"format": "png"})["data"])
        if path is not None:
            Path(path).write_bytes(png)
        return png


# What a MeshCat page exposes once its scene is in: JavaScript for Page.wait_for/evaluate.
MESHCAT_READY = "document.body && document.body.dataset.meshcatReady === '1'"


def _node(path: str) -> str:
    """JavaScript for the three.js object of a MeshCat node path such as ``/meshcat/a/b``."""
    return f"viewer.scene_tree.find({json.dumps([p for p in path.split('/') if p])}).object"


def capture_meshcat(html: str | Path, png: str | Path | None, *, width: int = 1200,
                    height: int = 750, time_s: float | None = None, controls: bool = True,
                    hide: tuple[str, ...] = (), project: tuple[str, ...] = ()) -> dict:
    """Open a MeshCat page (a file or a live server's URL), wait for its scene, optionally
    pause the animation at ``time_s`` and hide nodes, render, save a PNG screenshot and return
    facts read from the live viewer: animation duration and number of animated nodes, meshes
    in the scene, WebGL renderer, and the pixel position of each node in ``project``."""
    with Page(width, height) as page:
        page.open(str(html))
        if "://" in str(html) and not str(html).startswith("file:"):
            page.wait_for("typeof viewer !== 'undefined' && viewer.animator.duration > 0")
        else:
            page.wait_for(MESHCAT_READY)
        if time_s is not None:
            page.evaluate(f"viewer.animator.pause(); viewer.animator.seek({float(time_s)}); "
                          f"viewer.animator.display_progress({float(time_s)}); 1")
        if not controls:
            page.evaluate("viewer.gui.close(); 1")
        for path in hide:
            page.evaluate(f"{_node(path)}.visible = false; 1")
        page.evaluate("viewer.render(); 1")
        # Two animation frames so the canvas shows the rendered scene.
        page.evaluate("new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)))")
        facts = page.evaluate("""(() => {
            const a = viewer.animator;
            let meshes = 0;
            viewer.scene.traverse(o => { if (o.isMesh) meshes++; });
            const gl = viewer.renderer.getContext();
            return {duration: a.duration, actions: a.actions.length, meshes: meshes,
                    renderer: gl.getParameter(gl.RENDERER),
                    canvas: [viewer.renderer.domElement.width, viewer.renderer.domElement.height]};
        })()""")
        facts["screen"] = {}
        for path in project:
            facts["screen"][path] = page.evaluate(f"""(() => {{
                const o = {_node(path)};
                viewer.scene.updateMatrixWorld(true);
                const v = o.position.clone();
                o.getWorldPosition(v);
                v.project(viewer.camera);
                const c = viewer.renderer.domElement;
                return [(v.x + 1) / 2 * c.clientWidth, (1 - v.y) / 2 * c.clientHeight];
            }})()""")
        if png is not None:
            page.screenshot(png)
    return facts
