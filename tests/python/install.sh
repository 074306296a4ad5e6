#!/usr/bin/env bash
# Installs the build tree into a scratch prefix and imports the Python
# module from there (not from the build tree) with the build's interpreter.
#   install.sh BUILD_DIR PYTHON SITE_DIR (SITE_DIR relative to the prefix)
set -euo pipefail
build_dir="$1"; python="$2"; site="$3"
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
cmake --install "$build_dir" --prefix "$scratch/prefix" >/dev/null
cd "$scratch"
PYTHONPATH="$scratch/prefix/$site" "$python" -c '
import sys, contact2d
where = contact2d.__file__
assert where.startswith(sys.argv[1]), where
import pathlib  # the type stub and the PEP 561 marker beside the extension
assert all((pathlib.Path(where).parent / f).is_file() for f in ("_contact2d.pyi", "py.typed"))
s = contact2d.Scene("point_mass")
s.sim.duration = 0.01
print(where, contact2d.simulate(s).trajectory.shape)
' "$scratch/prefix/$site"
