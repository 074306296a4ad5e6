"""The PEP 517 backend of `pip install .` (pyproject.toml): builds the
extension _contact2d with CMake and packs it with the package's Python
files into a wheel. Standard library only, so pip needs nothing from an
index to run it (the machine reaches none). Its hooks: build_wheel,
build_sdist (the sources a build needs, with PKG-INFO) and build_editable
(PEP 660: a wheel whose .pth file imports contact2d from src/python and
its extension from the build tree).

Where it builds: CONTACT2D_BUILD_DIR (say build/, after scripts/setup:
only the module's target is brought up to date), else build-pip/ in the
source tree. A folder that is not a configured build yet is configured
here without the tests and benchmarks (neither GoogleTest nor Google
Benchmark is needed), with the libraries as unity builds, for the
interpreter that runs pip. Either way the extension must be built for that
interpreter: its file name's suffix (cpython-311-x86_64-linux-gnu) is
checked against the interpreter's before it is packed.

Build isolation: pip runs this backend with PYTHONPATH at a sitecustomize
that hides every site-packages but its own (empty) one, and the
interpreter CMake runs inherits it, so CMake's check for numpy (the module
needs it to run, though not to compile: pybind11's numpy.h has its own
declarations) failed. CMake runs without pip's PYTHONPATH and
PYTHONNOUSERSITE: it sees the interpreter as it will run the module.

The installed module runs the mujoco3 engine from src/mujoco3 of this
source tree (driver.mjs and node_modules, set up by scripts/setup), as a
`cmake --install` does; CONTACT2D_MUJOCO3_DIR moves it.
"""

import base64
import hashlib
import importlib.machinery
import io
import os
import pathlib
import re
import subprocess
import sys
import sysconfig
import tarfile
import zipfile

ROOT = pathlib.Path(__file__).resolve().parents[3]


def _version():
    text = (ROOT / "CMakeLists.txt").read_text(encoding="utf-8")
    match = re.search(r"project\(contact2d VERSION ([0-9.]+)", text)
    if not match:
        raise RuntimeError("contact2d: CMakeLists.txt has no 'project(contact2d VERSION x.y.z'")
    return match.group(1)


def _tag():
    interpreter = f"cp{sys.version_info.major}{sys.version_info.minor}"
    platform = sysconfig.get_platform().replace("-", "_").replace(".", "_")
    return f"{interpreter}-{interpreter}-{platform}"


def _run(command, env=None):
    print("contact2d:", " ".join(command), file=sys.stderr, flush=True)
    subprocess.run(command, check=True, stdout=sys.stderr, env=env)


def _outside_pip_isolation():
    """The environment without what pip's build isolation adds for Python
    (its sitecustomize's PYTHONPATH, PYTHONNOUSERSITE): the interpreter
    CMake asks about numpy then sees its own site-packages."""
    env = dict(os.environ)
    given = env["PYTHONPATH"].split(os.pathsep) if env.get("PYTHONPATH") else []
    kept = [p for p in given if "pip-build-env-" not in p]
    if len(kept) != len(given):
        env.pop("PYTHONNOUSERSITE", None)
        if kept:
            env["PYTHONPATH"] = os.pathsep.join(kept)
        else:
            del env["PYTHONPATH"]
    return env


def _build_dir():
    given = os.environ.get("CONTACT2D_BUILD_DIR", "")
    return pathlib.Path(given).resolve() if given else ROOT / "build-pip"


def _extension():
    """Builds the module's target and returns the built extension's path."""
    build = _build_dir()
    env = _outside_pip_isolation()
    if not (build / "CMakeCache.txt").is_file():
        # The libraries as unity builds (batches of 8 sources): the
        # from-scratch build's compile time, docs/python.md.
        _run(["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
              "-DCONTACT2D_WITH_TESTS=OFF", "-DCONTACT2D_WITH_BENCH=OFF",
              "-DCONTACT2D_WITH_WINDOW=OFF", "-DCONTACT2D_UNITY=libraries",
              "-DCONTACT2D_PYTHON=ON", f"-DPython3_EXECUTABLE={sys.executable}"], env)
    _run(["cmake", "--build", str(build), "--target", "contact2d_python", "-j",
          str(os.cpu_count() or 1)], env)
    suffix = importlib.machinery.EXTENSION_SUFFIXES[0]
    built = build / "python" / "contact2d" / f"_contact2d{suffix}"
    if not built.is_file():
        found = sorted(p.name for p in (build / "python" / "contact2d").glob("_contact2d*"))
        raise RuntimeError(f"contact2d: no _contact2d{suffix} for {sys.executable} in {build} "
                           f"(found: {', '.join(found) or 'none'}): that build is for another "
                           "Python; leave CONTACT2D_BUILD_DIR unset to build for this one")
    return built


# The package's Python files (src/python/contact2d), as the wheel holds them.
PACKAGE_FILES = ("__init__.py", "_contact2d.pyi", "py.typed")


def _metadata(header="Metadata-Version: 2.1\n"):
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    return (header +
            "Name: contact2d\n"
            f"Version: {_version()}\n"
            "Summary: A 2D rigid-body contact reference solver cross-validated against MuJoCo\n"
            "Requires-Python: >=3.9\n"
            "Requires-Dist: numpy\n"
            "Description-Content-Type: text/markdown\n\n" + readme)


def _record_line(name, data):
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return f"{name},sha256={digest},{len(data)}"


def get_requires_for_build_wheel(config_settings=None):
    return []


def get_requires_for_build_sdist(config_settings=None):
    return []


def get_requires_for_build_editable(config_settings=None):
    return []


def _dist_info():
    """The dist-info folder's name and its METADATA and WHEEL files."""
    info = f"contact2d-{_version()}.dist-info"
    return info, {
        f"{info}/METADATA": _metadata().encode(),
        f"{info}/WHEEL": ("Wheel-Version: 1.0\nGenerator: contact2d build_backend\n"
                          f"Root-Is-Purelib: false\nTag: {_tag()}\n").encode(),
    }


def prepare_metadata_for_build_wheel(metadata_directory, config_settings=None):
    """The metadata without building (pip asks for it first)."""
    info, files = _dist_info()
    for path, data in files.items():
        target = pathlib.Path(metadata_directory) / path
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(data)
    return info


prepare_metadata_for_build_editable = prepare_metadata_for_build_wheel


def _write_wheel(wheel_directory, files):
    """A wheel of `files` ({path in the wheel: bytes}) with its dist-info."""
    name = f"contact2d-{_version()}-{_tag()}.whl"
    info, dist_info = _dist_info()
    files = {**files, **dist_info}
    record = [_record_line(path, data) for path, data in files.items()]
    record.append(f"{info}/RECORD,,")
    files[f"{info}/RECORD"] = ("\n".join(record) + "\n").encode()
    # Written under a temporary name and renamed: no half-written wheel.
    target = pathlib.Path(wheel_directory) / name
    partial = target.with_name(name + ".partial")
    with zipfile.ZipFile(partial, "w", compression=zipfile.ZIP_DEFLATED) as wheel:
        for path, data in files.items():
            entry = zipfile.ZipInfo(path, date_time=(1980, 1, 1, 0, 0, 0))
            entry.external_attr = (0o755 if path.endswith(".so") else 0o644) << 16
            entry.compress_type = zipfile.ZIP_DEFLATED
            wheel.writestr(entry, data)
    os.replace(partial, target)
    return name


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    extension = _extension()
    files = {f"contact2d/{name}": (ROOT / "src/python/contact2d" / name).read_bytes()
             for name in PACKAGE_FILES}
    files[f"contact2d/{extension.name}"] = extension.read_bytes()
    return _write_wheel(wheel_directory, files)


# PEP 660: contact2d imported from src/python/contact2d (edits show at the
# next import) and its extension from the build tree (rebuilt by
# `cmake --build BUILD --target contact2d_python`), by a finder the .pth
# file installs: the package's __path__ holds both folders.
_EDITABLE_FINDER = """\
import importlib.util
import sys

SOURCE = {source!r}
BUILT = {built!r}


class ContactFinder:
    @classmethod
    def find_spec(cls, name, path=None, target=None):
        if name != "contact2d":
            return None
        return importlib.util.spec_from_file_location(
            name, SOURCE + "/__init__.py", submodule_search_locations=[SOURCE, BUILT])


def install():
    if ContactFinder not in sys.meta_path:
        sys.meta_path.append(ContactFinder)
"""


def build_editable(wheel_directory, config_settings=None, metadata_directory=None):
    extension = _extension()
    finder = _EDITABLE_FINDER.format(source=str(ROOT / "src/python/contact2d"),
                                     built=str(extension.parent))
    return _write_wheel(wheel_directory, {
        "_contact2d_editable_finder.py": finder.encode(),
        "_contact2d_editable.pth": b"import _contact2d_editable_finder; "
                                   b"_contact2d_editable_finder.install()\n",
    })


# What an sdist holds: what configuring and building the module reads (the
# CMake files, every library's sources, the package, this backend, the
# game's default pitch, which CMake reads while configuring), the README
# the metadata carries, and pyproject.toml. Not the tests, benchmarks,
# docs, models or the other validation data (the backend configures without
# tests and benchmarks). tests/python/pip_install.sh configures an unpacked
# sdist and checks that every file the module's build read is in it.
SDIST_ROOTS = ("CMakeLists.txt", "pyproject.toml", "README.md", "cmake/", "src/",
               "validation/scenes/game/pitch.toml")


def _sdist_files():
    """The files of SDIST_ROOTS: in a checkout, those git lists (tracked,
    or new and not ignored: a source added but not yet committed builds);
    else (an sdist's sdist) the files there are."""
    try:
        listed = subprocess.run(["git", "-C", str(ROOT), "ls-files", "-z", "--cached",
                                 "--others", "--exclude-standard", "--", *SDIST_ROOTS],
                                check=True, capture_output=True).stdout.decode().split("\0")
        names = sorted(n for n in listed if n and (ROOT / n).is_file())
    except (OSError, subprocess.CalledProcessError):
        names = sorted(str(p.relative_to(ROOT)) for root in SDIST_ROOTS
                       for p in ([ROOT / root] if not root.endswith("/")
                                 else (ROOT / root).rglob("*"))
                       if p.is_file() and "node_modules" not in p.parts
                       and "__pycache__" not in p.parts)
    return names


def build_sdist(sdist_directory, config_settings=None):
    base = f"contact2d-{_version()}"
    name = f"{base}.tar.gz"
    target = pathlib.Path(sdist_directory) / name
    partial = target.with_name(name + ".partial")

    def add(tar, path, data, mode=0o644):
        entry = tarfile.TarInfo(f"{base}/{path}")
        entry.size, entry.mode, entry.mtime = len(data), mode, 0
        entry.uname = entry.gname = "root"
        tar.addfile(entry, io.BytesIO(data))

    with tarfile.open(partial, "w:gz", format=tarfile.PAX_FORMAT) as tar:
        add(tar, "PKG-INFO", _metadata("Metadata-Version: 2.2\n").encode())
        for path in _sdist_files():
            file = ROOT / path
            add(tar, path, file.read_bytes(), 0o755 if os.access(file, os.X_OK) else 0o644)
    os.replace(partial, target)
    return name
