"""A fresh interpreter that must stay silent on stderr (the package's imports and warnings
checked at the file-descriptor level): shared by the model tests."""
import os
import subprocess
import sys
import textwrap


def run_clean(tmp_path, code: str) -> str:
    """Run ``code`` in a fresh interpreter; return its stdout after checking it was silent on
    stderr (fd level: C++ and Python warnings alike)."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONWARNINGS"}
    out = subprocess.run([sys.executable, "-W", "always", "-c", textwrap.dedent(code)],
                         cwd=tmp_path, capture_output=True, text=True, timeout=120, env=env)
    assert out.returncode == 0, out.stderr
    assert out.stderr == "", out.stderr
    return out.stdout
