"""Errors are Python exceptions with the program's one-line message (the
program's stderr line without "contact2d: "), never a crash."""

import threading
import time

import numpy as np
import pytest

import contact2d
from conftest import SOURCE_DIR as SOURCE, program_error, run_program

BOX = "validation/scenes/box.toml"


def test_missing_scene_file():
    message = program_error("simulate", "no/such/scene.toml")
    with pytest.raises(FileNotFoundError) as e:
        contact2d.Scene.load("no/such/scene.toml")
    assert str(e.value) == message


def test_bad_value_in_file(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text('scene = "box"\n[contact]\nk = -5\n')
    message = program_error("simulate", str(path))
    with pytest.raises(ValueError) as e:
        contact2d.Scene.load(str(path))
    assert str(e.value) == message


def test_bad_value_set_in_python(tmp_path):
    # A value set from Python is named as the scene file would name it.
    path = tmp_path / "scene.toml"
    path.write_text('scene = "box"\n')
    scene = contact2d.Scene.load(str(path))
    path.write_text('scene = "box"\n[contact]\nk = -5\n')
    message = program_error("simulate", str(path))
    scene.contact.k = -5
    for call in (contact2d.simulate, contact2d.compare, contact2d.generate,
                 contact2d.Scene.validate):
        with pytest.raises(ValueError) as e:
            call(scene)
        assert str(e.value) == message


def test_bad_override():
    # The program's line, its option as the keyword: --set contact.c=-1 is set=["contact.c=-1"].
    message = program_error("simulate", BOX, "--set", "contact.c=-1")
    assert message.startswith("--set contact.c=-1: ")
    with pytest.raises(ValueError) as e:
        contact2d.Scene.load(BOX, set=["contact.c=-1"])
    assert str(e.value) == 'set=["contact.c=-1"]: ' + message.split(": ", 1)[1]


def test_bad_names():
    scene = contact2d.Scene.load(BOX)
    with pytest.raises(ValueError, match="is not an integrator"):
        scene.sim.integrator = "leapfrog"
    with pytest.raises(ValueError, match="is not a damping law"):
        scene.contact.damping = "viscous"
    with pytest.raises(ValueError, match="is not a friction law"):
        scene.contact.friction_law = "coulomb"
    with pytest.raises(ValueError, match="is not a scene"):
        scene.shape = "sphere"
    with pytest.raises(ValueError):
        contact2d.simulate(scene, engine="bullet")
    with pytest.raises(ValueError):
        contact2d.generate(scene, mapping="nosuch")


def test_explicit_euler_in_mujoco():
    message = program_error("compare", BOX, "--integrator", "explicit_euler")
    with pytest.raises(ValueError) as e:
        contact2d.compare(contact2d.Scene.load(BOX), integrator="explicit_euler")
    assert str(e.value) == message


def test_divergence():
    path = "tests/cli/bad_inputs/diverging_dt.toml"
    message = program_error("simulate", path, "--integrator", "explicit_euler", "--dt", "0.005",
                            status=3)
    # The hint names the keywords: "Try --dt 7.9e-05 or --integrator semi_implicit_euler."
    assert message.endswith("Try --dt 7.9e-05 or --integrator semi_implicit_euler.")
    with pytest.raises(RuntimeError) as e:
        contact2d.simulate(contact2d.Scene.load(path), integrator="explicit_euler", dt=0.005)
    assert str(e.value) == message.replace(
        "Try --dt 7.9e-05 or --integrator semi_implicit_euler.",
        'Try dt=7.9e-05 or integrator="semi_implicit_euler".')


def test_not_physics():
    path = "tests/cli/bad_inputs/nonphysical_sunk.toml"
    message = program_error("simulate", path, status=3)
    reason = message.split("not physics: ", 1)[1].rsplit(". Pass --allow-nonphysical", 1)[0]
    scene = contact2d.Scene.load(path)
    with pytest.raises(RuntimeError) as e:
        contact2d.simulate(scene)
    assert str(e.value) == f"{path}: not physics: {reason}. Pass allow_nonphysical=True to keep the run."
    run = contact2d.simulate(scene, allow_nonphysical=True)
    assert run.warnings[-1].endswith(reason)


def test_solref_errors():
    message = program_error("solref", "--k", "-1", "--c", "1", "--dt", "1e-3", "--mass", "1")
    assert message.startswith("--k -1: ")
    with pytest.raises(ValueError) as e:
        contact2d.solref(k=-1, c=1, dt=1e-3, mass=1)
    assert str(e.value) == "k=-1: " + message.split(": ", 1)[1]
    message = program_error("solref", "--k", "1e4", "--c", "1", "--dt", "1e-3",
                            "--model", "no/such.xml", "--body", "b")
    assert message.startswith("--model no/such.xml: ")
    with pytest.raises(FileNotFoundError) as e:
        contact2d.solref(k=1e4, c=1, dt=1e-3, model="no/such.xml", body="b")
    assert str(e.value) == 'model="no/such.xml": ' + message.split(": ", 1)[1]


def test_solref_mass_with_model_is_refused():
    """The CLI refuses --mass with --model; the module used to drop the mass."""
    with pytest.raises(ValueError) as e:
        contact2d.solref(k=1e4, c=1, dt=1e-3, mass=2, model="docs/examples/box_on_plane.xml",
                         body="box")
    assert str(e.value).startswith("mass=2: not with model= ")  # "--mass 2: not with --model"


def test_inspect_missing_file():
    message = program_error("inspect", "no/such.xml")
    with pytest.raises(FileNotFoundError) as e:
        contact2d.inspect("no/such.xml")
    assert str(e.value) == message


def test_gil_released_while_running():
    # While another thread simulates, this one keeps running Python: the
    # engine runs without the GIL. Held, this loop would stop for the whole
    # run; released, its longest pause is a scheduling slice.
    scene = contact2d.Scene.load(BOX)
    scene.sim.duration = 100.0
    done = threading.Event()

    def work():
        contact2d.simulate(scene, integrator="rk4")
        done.set()

    thread = threading.Thread(target=work)
    start = last = time.perf_counter()
    thread.start()
    longest = 0.0
    while not done.is_set():
        now = time.perf_counter()
        longest = max(longest, now - last)
        last = now
        time.sleep(0.001)
    thread.join()
    elapsed = time.perf_counter() - start
    assert elapsed > 0.1 and longest < 0.5 * elapsed, (elapsed, longest)


@pytest.mark.parametrize("value", [float("nan"), -1.0, 0.0, float("inf"), 1e300, 2.0])
def test_model_dt_takes_the_cli_range(value):
    """model_dt is --model-dt: (0, 1] s, or None (the timestep); anything else is
    the one-line error, for every function that takes it."""
    scene = contact2d.Scene.load("validation/scenes/box.toml")
    for call in (lambda: contact2d.simulate(scene, engine="mujoco", model_dt=value),
                 lambda: contact2d.compare(scene, model_dt=value, diagnosis=False),
                 lambda: contact2d.generate(scene, model_dt=value)):
        with pytest.raises(ValueError, match=r"model_dt = .* is out of range: must be in \(0, 1\] s"):
            call()
    assert contact2d.generate(scene, model_dt=1e-3).startswith("<!--")


def test_a_scene_file_path_is_a_scene():
    """simulate, compare and generate take a path (str or pathlib) as
    Scene.load would read it: the same numbers ("Unable to cast Python
    instance to C++ type" before)."""
    from pathlib import Path
    path = "validation/scenes/box.toml"
    by_scene = contact2d.simulate(contact2d.Scene.load(path), duration=0.1)
    for given in (path, Path(path)):
        by_path = contact2d.simulate(given, duration=0.1)
        assert np.array_equal(by_path.trajectory, by_scene.trajectory)
    assert contact2d.generate(path) == contact2d.generate(contact2d.Scene.load(path))


def test_a_wrong_type_names_the_function_and_the_keyword():
    """A string for a number, or a number for the scene, is a TypeError of
    the public function with the keyword and its unit (it named the
    internal _simulate())."""
    scene = contact2d.Scene.load("validation/scenes/box.toml")
    with pytest.raises(TypeError, match=r"^simulate\(\): dt must be a number \(s\), not str '1e-3'"):
        contact2d.simulate(scene, dt="1e-3")
    with pytest.raises(TypeError, match=r"^simulate\(\): duration must be a number"):
        contact2d.simulate(scene, duration=True)
    with pytest.raises(TypeError, match=r"^compare\(\): scene must be a contact2d.Scene or the "
                                        r"path of a scene file, not int"):
        contact2d.compare(5)
    with pytest.raises(FileNotFoundError):
        contact2d.simulate("no/such/scene.toml")


def test_version_is_the_programs():
    """__version__ is the project's version, as `contact2d --version` prints it."""
    out, _ = run_program("--version")
    assert out.split()[1] == contact2d.__version__


def test_a_path_with_a_nul_is_refused():
    # The C library stopped the path at the NUL: 'box.toml\x00junk' loaded box.toml.
    path = str(SOURCE / "validation/scenes/box.toml") + "\x00junk"
    with pytest.raises(ValueError, match="NUL character"):
        contact2d.Scene.load(path)
    with pytest.raises(ValueError, match="NUL character"):
        contact2d.simulate(path)
    with pytest.raises(ValueError, match="NUL character"):
        contact2d.inspect(str(SOURCE / "docs/examples/inspect.xml") + "\x00x")


def test_settle_none_names_the_keyword():
    # pybind11's raw "incompatible function arguments" before.
    with pytest.raises(TypeError, match=r"inspect\(\): settle must be a number \(s\), not None"):
        contact2d.inspect(str(SOURCE / "docs/examples/inspect.xml"), settle=None)
    with pytest.raises(TypeError, match=r"solref\(\): settle must be a number \(s\), not None"):
        contact2d.solref(k=1e4, c=10, dt=1e-3, mass=1, settle=None)
