#!/usr/bin/env bash
# docs/python.md's commands, configure and compile included: a scratch
# virtual environment that sees Debian's numpy, `pip install --no-index .`
# with build isolation on (pip's default), and the module imported from
# outside the tree. The build goes to a scratch folder (CONTACT2D_BUILD_DIR,
# not configured yet: the backend configures it as it does build-pip/), so
# every run configures and compiles the module and its libraries from
# nothing: 130 s of CPU on this machine, ctest label pip_build
# (docs/python.md). It prints the seconds the install took.
#   pip_from_scratch.sh SOURCE_DIR PYTHON VERSION
set -euo pipefail
source_dir="$(cd "$1" && pwd)"; python="$2"; version="$3"
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
export PIP_DISABLE_PIP_VERSION_CHECK=1 PYTHONDONTWRITEBYTECODE=1
"$python" -m venv --system-site-packages "$scratch/env"
start=$(date +%s.%N)
CONTACT2D_BUILD_DIR="$scratch/build" "$scratch/env/bin/pip" install --no-index "$source_dir" \
  > "$scratch/pip.log" 2>&1 || { tail -40 "$scratch/pip.log"; exit 1; }
end=$(date +%s.%N)
grep -q '^CONTACT2D_UNITY:STRING=libraries$' "$scratch/build/CMakeCache.txt"  # configured here
cd "$scratch"
"$scratch/env/bin/python" -c '
import pathlib, sys, contact2d
assert pathlib.Path(sys.argv[1]) in pathlib.Path(contact2d.__file__).parents, contact2d.__file__
assert contact2d.__version__ == sys.argv[2], contact2d.__version__
s = contact2d.Scene("box")
s.sim.duration = 0.05
print(contact2d.__file__, contact2d.__version__, contact2d.simulate(s).trajectory.shape)
' "$scratch/env" "$version"
echo "pip install --no-index . from scratch (configure + build + install): $("$python" -c "print(round($end - $start, 1))") s"
