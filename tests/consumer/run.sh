#!/usr/bin/env bash
# Installs the build tree into a scratch prefix, checks its include tree
# (the public headers only), then configures, builds and runs
# tests/consumer against it: a project that needs neither GoogleTest nor
# Google Benchmark (the installed package asks only for Eigen).
set -euo pipefail
build_dir="$1"; source_dir="$2"
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
cmake --install "$build_dir" --prefix "$scratch/prefix" >/dev/null
# The installed headers are contact2d.hpp and what it includes, nothing
# more and nothing less.
include="$scratch/prefix/include/contact2d"
python3 - "$include" <<'PY'
import os, re, sys
root = sys.argv[1]
installed = {os.path.relpath(os.path.join(d, f), root)
             for d, _, files in os.walk(root) for f in files}
reached, todo = set(), ["contact2d.hpp"]
while todo:
    header = todo.pop()
    if header in reached:
        continue
    reached.add(header)
    path = os.path.join(root, header)
    if not os.path.isfile(path):
        sys.exit(f"run.sh: {header} is included but not installed")
    todo += re.findall(r'#include "([^"]+)"', open(path, encoding="utf-8").read())
if installed != reached:
    sys.exit(f"run.sh: installed but not reached from contact2d.hpp: {sorted(installed - reached)}")
print(f"{len(installed)} public headers installed, each reached from contact2d.hpp")
PY
cmake -S "$source_dir" -B "$scratch/build" -DCMAKE_PREFIX_PATH="$scratch/prefix" >/dev/null
cmake --build "$scratch/build" >/dev/null
"$scratch/build/consumer"
