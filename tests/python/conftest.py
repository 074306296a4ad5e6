"""Fixtures of the Python module's tests (tests/python/CMakeLists.txt runs
them under ctest with PYTHONPATH at the build tree's package).

CONTACT2D_PROGRAM is the contact2d program of the same build, whose output
the module's numbers are checked against; CONTACT2D_DIGEST its
contact2d_digest (absent when the build has no bench/). Paths are relative
to the source tree, the tests' working directory, so that the program and
the module see the same file names (they appear in messages and in the
generated MJCF's header)."""

import os
import subprocess
from pathlib import Path

import pytest

SOURCE_DIR = Path(__file__).resolve().parents[2]
SCENES = ["validation/scenes/box.toml", "validation/scenes/circle.toml",
          "validation/scenes/point_mass.toml", "validation/scenes/tshape.toml"]


def needs(present, what_is_missing):
    """Skips a test that needs what the machine lacks (MuJoCo built in, the
    program, the bench), unless CONTACT2D_REQUIRE_DEPENDENCIES is set (by
    scripts/test, where scripts/setup installs everything), where it fails:
    there a skip would hide a broken install."""
    if present:
        return
    if os.environ.get("CONTACT2D_REQUIRE_DEPENDENCIES"):
        pytest.fail(f"{what_is_missing} (CONTACT2D_REQUIRE_DEPENDENCIES: scripts/setup installs it)")
    pytest.skip(what_is_missing)


@pytest.fixture(autouse=True)
def in_source_dir(monkeypatch):
    monkeypatch.chdir(SOURCE_DIR)


def program_path():
    path = os.environ.get("CONTACT2D_PROGRAM", str(SOURCE_DIR / "build" / "contact2d"))
    needs(Path(path).exists(), f"no contact2d program at {path} (set CONTACT2D_PROGRAM)")
    return path


def run_program(*args, status=0):
    """contact2d ARGS: (stdout, stderr), checking the exit status."""
    done = subprocess.run([program_path(), *args], capture_output=True, text=True,
                          cwd=SOURCE_DIR, check=False)
    assert done.returncode == status, (args, done.returncode, done.stderr)
    return done.stdout, done.stderr


def program_error(*args, status=2):
    """The program's one-line message for ARGS, without "contact2d: "."""
    _, err = run_program(*args, status=status)
    lines = err.strip().splitlines()
    assert len(lines) == 1, lines
    assert lines[0].startswith("contact2d: ")
    return lines[0][len("contact2d: "):]
