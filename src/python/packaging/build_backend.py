"""The PEP 517 backend of `pip install .` (pyproject.toml): builds the
extension _contact2d with CMake and packs it with contact2d/__init__.py
into a wheel. Standard library only, so pip needs nothing from an index to
run it (the machine reaches none).

Where it builds: the configured build tree named by CONTACT2D_BUILD_DIR
(say build/, after scripts/setup: only the module's target is brought up
to date), else build-pip/ in the source tree, configured here without the
tests and benchmarks (neither GoogleTest nor Google Benchmark is needed)
for the interpreter that runs pip. Either way the extension must be built
for that interpreter: its file name's suffix (cpython-311-x86_64-linux-gnu)
is checked against the interpreter's before it is packed.

The installed module runs the mujoco3 engine from src/mujoco3 of this
source tree (driver.mjs and node_modules, set up by scripts/setup), as a
`cmake --install` does; CONTACT2D_MUJOCO3_DIR moves it.
"""

import base64
import hashlib
import importlib.machinery
import os
import pathlib
import re
import subprocess
import sys
import sysconfig
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


def _run(command):
    print("contact2d:", " ".join(command), file=sys.stderr, flush=True)
    subprocess.run(command, check=True, stdout=sys.stderr)


def _extension():
    """Builds the module's target and returns the built extension's path."""
    given = os.environ.get("CONTACT2D_BUILD_DIR", "")
    build = pathlib.Path(given).resolve() if given else ROOT / "build-pip"
    if given and not (build / "CMakeCache.txt").is_file():
        raise RuntimeError(f"contact2d: CONTACT2D_BUILD_DIR={given} is not a configured build "
                           "(run scripts/setup, or leave it unset to build in build-pip/)")
    if not given:
        _run(["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
              "-DCONTACT2D_WITH_TESTS=OFF", "-DCONTACT2D_WITH_BENCH=OFF",
              "-DCONTACT2D_PYTHON=ON", f"-DPython3_EXECUTABLE={sys.executable}"])
    _run(["cmake", "--build", str(build), "--target", "contact2d_python", "-j",
          str(os.cpu_count() or 1)])
    suffix = importlib.machinery.EXTENSION_SUFFIXES[0]
    built = build / "python" / "contact2d" / f"_contact2d{suffix}"
    if not built.is_file():
        found = sorted(p.name for p in (build / "python" / "contact2d").glob("_contact2d*"))
        raise RuntimeError(f"contact2d: no _contact2d{suffix} for {sys.executable} in {build} "
                           f"(found: {', '.join(found) or 'none'}): that build is for another "
                           "Python; leave CONTACT2D_BUILD_DIR unset to build for this one")
    return built


def _metadata():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    return ("Metadata-Version: 2.1\n"
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


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    extension = _extension()
    name = f"contact2d-{_version()}-{_tag()}.whl"
    info, files = _dist_info()
    files = {
        "contact2d/__init__.py": (ROOT / "src/python/contact2d/__init__.py").read_bytes(),
        f"contact2d/{extension.name}": extension.read_bytes(),
        **files,
    }
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
