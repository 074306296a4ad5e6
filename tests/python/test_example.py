"""examples/python/compare_mappings.py runs headless and writes its PNG."""

import os
import subprocess
import sys

from conftest import SOURCE_DIR


def test_compare_mappings_example(tmp_path):
    out = tmp_path / "mappings.png"
    env = dict(os.environ, MPLBACKEND="Agg")
    env.pop("DISPLAY", None)
    done = subprocess.run([sys.executable, "examples/python/compare_mappings.py", "--out",
                           str(out)], capture_output=True, text=True, cwd=SOURCE_DIR, env=env,
                          check=False)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines()[-1] == str(out)
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "calibrated: max position difference" in done.stdout
