#!/usr/bin/env bash
# The backend's three PEP 517 builds (src/python/packaging/build_backend.py)
# from the configured build tree BUILD_DIR (CONTACT2D_BUILD_DIR: no
# compiling beyond bringing the module's target up to date), with no package
# index (--no-index: the machine reaches none) and build isolation on
# (pip's default) unless said:
#  1. `pip install .` into a scratch virtual environment that sees Debian's
#     numpy (--system-site-packages), and with --no-build-isolation into
#     another; then, from outside the tree, the module
#     is the installed one, its __version__ is the project's, it runs a
#     scene, and the installed files are the wheel's (RECORD) and nothing else;
#  2. `pip install -e .` into another: contact2d is imported from
#     src/python/contact2d and its extension from BUILD_DIR;
#  3. build_sdist (no frontend for it is installed: python3-build is not, so
#     the hook is called as a frontend calls it): the tarball has PKG-INFO,
#     every file the module's build in BUILD_DIR read from the source tree
#     (the compiler's depfiles of the module and of every library it links),
#     and an unpacked copy configures as the backend configures it.
# The from-scratch configure and build of `pip install .` is
# pip_from_scratch.sh (label pip_build: it compiles for minutes).
#   pip_install.sh SOURCE_DIR BUILD_DIR PYTHON VERSION
set -euo pipefail
source_dir="$(cd "$1" && pwd)"; build_dir="$(cd "$2" && pwd)"; python="$3"; version="$4"
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
export PIP_DISABLE_PIP_VERSION_CHECK=1 PYTHONDONTWRITEBYTECODE=1

# 1. pip install ., with build isolation (pip's default) and without
cd "$scratch"
for isolation in "" --no-build-isolation; do
venv="$scratch/venv$isolation"
"$python" -m venv --system-site-packages "$venv"
CONTACT2D_BUILD_DIR="$build_dir" "$venv/bin/pip" install --quiet --no-index $isolation \
  "$source_dir"
"$venv/bin/python" - "$venv" "$version" "${isolation:-(build isolation on)}" <<'PY'
import importlib.metadata, pathlib, sys
import contact2d
venv, version = pathlib.Path(sys.argv[1]), sys.argv[2]
where = pathlib.Path(contact2d.__file__)
assert venv in where.parents, where
assert contact2d.__version__ == version, (contact2d.__version__, version)
assert importlib.metadata.version("contact2d") == version
files = sorted(str(f) for f in importlib.metadata.files("contact2d"))
extension = next(where.parent.glob("_contact2d*.so")).name
assert [f for f in files if not f.startswith("contact2d-") and "__pycache__" not in f] == \
    ["contact2d/" + name for name in sorted(["__init__.py", "_contact2d.pyi", "py.typed",
                                             extension])], files
s = contact2d.Scene("point_mass")
s.sim.duration = 0.01
print("pip install", sys.argv[3], ".:", where, contact2d.__version__,
      contact2d.simulate(s).trajectory.shape)
PY
done

# 2. pip install -e .
"$python" -m venv --system-site-packages "$scratch/editable"
CONTACT2D_BUILD_DIR="$build_dir" "$scratch/editable/bin/pip" install --quiet --no-index \
  -e "$source_dir"
"$scratch/editable/bin/python" - "$source_dir" "$build_dir" "$version" <<'PY'
import importlib.metadata, pathlib, sys
import contact2d
source, build, version = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2]), sys.argv[3]
assert pathlib.Path(contact2d.__file__) == source / "src/python/contact2d/__init__.py", \
    contact2d.__file__
assert pathlib.Path(contact2d._contact2d.__file__).parent == build / "python/contact2d", \
    contact2d._contact2d.__file__
assert importlib.metadata.version("contact2d") == version
s = contact2d.Scene("point_mass")
s.sim.duration = 0.01
print("pip install -e .:", contact2d.__file__, contact2d._contact2d.__file__,
      contact2d.simulate(s).trajectory.shape)
PY

# 3. build_sdist
mkdir "$scratch/sdist"
(cd "$source_dir" && "$python" -c '
import sys
sys.path.insert(0, "src/python/packaging")  # pyproject.toml: backend-path
import build_backend
print(build_backend.build_sdist(sys.argv[1]))' "$scratch/sdist") > "$scratch/sdist_name"
sdist="$scratch/sdist/$(cat "$scratch/sdist_name")"
[ "$(basename "$sdist")" = "contact2d-$version.tar.gz" ]
"$python" - "$sdist" "$source_dir" "$build_dir" "$version" <<'PY'
import pathlib, re, sys, tarfile
sdist, source, build, version = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3]), sys.argv[4]
base = f"contact2d-{version}/"
with tarfile.open(sdist) as tar:
    names = {m.name[len(base):] for m in tar.getmembers() if m.name.startswith(base)}
    pkg_info = tar.extractfile(base + "PKG-INFO").read().decode()
assert f"\nName: contact2d\nVersion: {version}\n" in pkg_info, pkg_info[:200]
for needed in ("pyproject.toml", "CMakeLists.txt", "src/python/packaging/build_backend.py",
               "src/python/contact2d/__init__.py", "src/python/contact2d/_contact2d.pyi",
               "src/python/contact2d/py.typed", "src/python/module.cpp"):
    assert needed in names, needed
# Every file of the source tree the module's build read: the depfiles of
# the module and of each library its link line names. Files the build wrote
# itself (a unity batch, build/CMakeFiles/*/Unity/*.cxx, when the build
# folder is inside the tree) are not sources.
link = (build / "src/python/CMakeFiles/contact2d_python.dir/link.txt").read_text()
targets = ["src/python/CMakeFiles/contact2d_python.dir"] + \
    [f"CMakeFiles/{name}.dir" for name in re.findall(r"lib(contact2d_\w+)\.a", link)]
read = set()
for target in targets:
    depfiles = list((build / target).rglob("*.o.d"))
    assert depfiles, target
    for depfile in depfiles:
        for token in depfile.read_text().replace("\\\n", " ").split():
            path = pathlib.Path(token)
            if (not token.endswith(":") and path.is_absolute() and source in path.parents
                    and build not in path.parents):
                read.add(str(path.relative_to(source)))
missing = sorted(read - names)
assert len(read) > 50 and not missing, (len(read), missing)
print(f"sdist: {len(names)} files; the {len(read)} source files {len(targets)} targets' "
      "builds read are all in it")
PY
tar xzf "$sdist" -C "$scratch/sdist"
cmake -S "$scratch/sdist/contact2d-$version" -B "$scratch/sdist/build" -DCMAKE_BUILD_TYPE=Release \
  -DCONTACT2D_WITH_TESTS=OFF -DCONTACT2D_WITH_BENCH=OFF -DCONTACT2D_WITH_WINDOW=OFF \
  -DCONTACT2D_UNITY=libraries -DCONTACT2D_PYTHON=ON "-DPython3_EXECUTABLE=$python" >/dev/null
echo "sdist: configures"
