#!/usr/bin/env bash
# `pip install .` of the source tree into a scratch virtual environment
# (it sees Debian's numpy: --system-site-packages), with no package index
# (--no-index: the machine reaches none) and build isolation on, so the
# backend (src/python/packaging/build_backend.py) must need nothing from an
# index; the extension comes from the configured build tree
# (CONTACT2D_BUILD_DIR). Then, from outside the tree: the module is the
# installed one, its __version__ is the project's, it runs a scene, and the
# installed files are the wheel's (RECORD) and nothing else.
#   pip_install.sh SOURCE_DIR BUILD_DIR PYTHON VERSION
set -euo pipefail
source_dir="$1"; build_dir="$2"; python="$3"; version="$4"
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
"$python" -m venv --system-site-packages "$scratch/venv"
CONTACT2D_BUILD_DIR="$build_dir" PIP_DISABLE_PIP_VERSION_CHECK=1 \
  "$scratch/venv/bin/pip" install --quiet --no-index "$source_dir"
cd "$scratch"
PYTHONDONTWRITEBYTECODE=1 "$scratch/venv/bin/python" - "$scratch/venv" "$version" <<'PY'
import importlib.metadata, pathlib, sys
import contact2d
venv, version = pathlib.Path(sys.argv[1]), sys.argv[2]
where = pathlib.Path(contact2d.__file__)
assert venv in where.parents, where
assert contact2d.__version__ == version, (contact2d.__version__, version)
assert importlib.metadata.version("contact2d") == version
files = sorted(str(f) for f in importlib.metadata.files("contact2d"))
assert [f for f in files if not f.startswith("contact2d-") and "__pycache__" not in f] == \
    ["contact2d/__init__.py", "contact2d/" + next(where.parent.glob("_contact2d*")).name], files
s = contact2d.Scene("point_mass")
s.sim.duration = 0.01
print(where, contact2d.__version__, contact2d.simulate(s).trajectory.shape)
PY
