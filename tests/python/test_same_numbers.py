"""The module's numbers are the program's, bit for bit.

JSON results (compare, solref, inspect) are compared as parsed objects,
the wall-clock fields excepted, the program's texts in Python's words
(python_json: "--dt 0.0002" is "dt=0.0002", each diagnosis's fix with its
fix_kwargs; test_python_words.py checks those words); the MJCF of generate as text. Trajectories:
the program writes them as CSV at %.10g (t) and %.12g (states), so every
sample of the module's arrays, printed the same way, must give the CSV's
text exactly; and the reference's final state, which contact2d_digest
prints exactly (%a), must be the same double."""

import json
import os
import subprocess
import warnings
from pathlib import Path

import numpy as np
import pytest

import contact2d
from conftest import SCENES, SOURCE_DIR, needs, program_path, run_program

TIMINGS = ("ref_seconds", "mujoco_seconds", "converged_seconds")


def python_json(out, diagnosis=False):
    """The program's --json output as the module gives it: its numbers,
    its texts in Python's words (contact2d's one table of options)."""
    parsed = json.loads(out)
    if diagnosis:
        parsed = contact2d._with_fixes(parsed)
    return contact2d._translated(parsed)


def masked(result):
    return {k: v for k, v in result.items() if k not in TIMINGS}


def csv_rows(array, state_format="%.12g"):
    """The rows of io/csv.cpp's write_trajectory_row for an N × 7 array."""
    return [",".join(["%.10g" % row[0]] + [state_format % v for v in row[1:]]) for row in array]


def read_csv(path):
    lines = Path(path).read_text().splitlines()
    return lines[0], lines[1:]


@pytest.mark.parametrize("scene", SCENES)
def test_compare_json_and_trajectories(scene, tmp_path):
    csv = tmp_path / "compare.csv"
    out, _ = run_program("compare", scene, "--json", "--csv", str(csv))
    result = contact2d.compare(contact2d.Scene.load(scene))
    expected = python_json(out, diagnosis=True)
    for key in TIMINGS:
        assert key in result
    assert masked({k: v for k, v in result.items() if not k.endswith("_trajectory")
                   and k not in ("warnings", "text")}) == masked(expected)
    header, rows = read_csv(csv)
    ref, mujoco, conv = (result["ref_trajectory"], result["mujoco_trajectory"],
                         result["converged_trajectory"])
    n = min(len(ref), len(mujoco))
    parts = [csv_rows(ref[:n]), [r.split(",", 1)[1] for r in csv_rows(mujoco[:n])]]
    if conv is not None:
        parts.append([r.split(",", 1)[1] for r in csv_rows(conv[:n])])
    assert header.count(",") + 1 == 7 + 6 * (len(parts) - 1)
    assert [",".join(p) for p in zip(*parts)] == rows


@pytest.mark.parametrize("scene", SCENES)
def test_compare_text_is_what_the_program_prints(scene):
    """result["text"] is compare's table and diagnosis, line for line (the
    wall-clock line masked: it is a measurement of each run)."""
    out, _ = run_program("compare", scene)
    text = contact2d.compare(contact2d.Scene.load(scene))["text"]
    def unclocked(lines):
        return [line for line in lines.splitlines() if not line.startswith("wall clock")]
    assert unclocked(text) == unclocked(out)
    assert "Diagnosis" in text


def test_compare_engines_list(tmp_path):
    """compare(engines=...) is --engines: the same JSON, every engine's trajectory."""
    scene = "validation/scenes/box.toml"
    engines = ["mujoco:exact", "mujoco:calibrated:boxes"]
    out, _ = run_program("compare", scene, "--json", "--engines", ",".join(engines),
                         "--duration", "0.5", "--no-diagnosis", "--allow-nonphysical")
    result = contact2d.compare(contact2d.Scene.load(scene), engines=engines, duration=0.5,
                               diagnosis=False, allow_nonphysical=True)
    expected = python_json(out, diagnosis=True)
    timings = TIMINGS + ("mujoco_exact_seconds", "mujoco_calibrated_boxes_seconds")
    assert ({k: v for k, v in result.items() if not k.endswith("_trajectory")
             and k not in ("warnings", "text") and k not in timings}
            == {k: v for k, v in expected.items() if k not in timings})
    assert set(expected["integrators"]) == {"ref", "mujoco_exact", "mujoco_calibrated_boxes"}
    for key in ("ref", "mujoco_exact", "mujoco_calibrated_boxes"):
        assert result[key + "_trajectory"].shape[1] == 7
    with pytest.raises(ValueError, match="with engines = an engine's options are part"):
        contact2d.compare(contact2d.Scene.load(scene), engines=engines, mapping="exact")


def test_compare_options(tmp_path):
    scene = "validation/scenes/point_mass.toml"
    args = ["--set", "contact.damping=kelvin_voigt", "--set", "contact.mu=0"]
    out, _ = run_program("compare", scene, *args, "--json", "--mapping", "compensated",
                         "--integrator", "rk4", "--dt", "2e-4", "--no-diagnosis")
    s = contact2d.Scene.load(scene, set=["contact.damping=kelvin_voigt", "contact.mu=0"])
    result = contact2d.compare(s, mapping="compensated", integrator="rk4", dt=2e-4,
                               diagnosis=False)
    assert masked({k: v for k, v in result.items() if not k.endswith("_trajectory")
                   and k not in ("warnings", "text")}) == masked(python_json(out, diagnosis=True))


@pytest.mark.parametrize("engine", ["ref", "mujoco"])
@pytest.mark.parametrize("scene", SCENES)
def test_simulate_csv(scene, engine, tmp_path):
    csv = tmp_path / "run.csv"
    run_program("simulate", scene, "--engine", engine, "--csv", str(csv))
    run = contact2d.simulate(contact2d.Scene.load(scene), engine=engine)
    header, rows = read_csv(csv)
    assert header == ",".join(run.columns) == ",".join(contact2d.COLUMNS)
    assert run.trajectory.dtype == np.float64 and run.trajectory.shape == (len(rows), 7)
    assert csv_rows(run.trajectory) == rows
    assert run.summary.startswith(contact2d.Scene.load(scene).shape + " [" + engine + ", ")


def digest_path():
    path = os.environ.get("CONTACT2D_DIGEST",
                          str(Path(program_path()).parent / "bench" / "contact2d_digest"))
    needs(Path(path).exists(), f"no contact2d_digest at {path} (a build without bench/)")
    return path


@pytest.mark.parametrize("scene", SCENES)
def test_reference_final_state_exact(scene):
    lines = subprocess.run([digest_path(), scene], capture_output=True, text=True, check=True,
                           cwd=SOURCE_DIR).stdout.splitlines()
    for line in lines:
        words = line.split()
        integrator = words[1]
        q = [float.fromhex(w) for w in words[words.index("q") + 1:words.index("q") + 4]]
        v = [float.fromhex(w) for w in words[words.index("v") + 1:words.index("v") + 4]]
        run = contact2d.simulate(contact2d.Scene.load(scene), integrator=integrator)
        assert list(run.trajectory[-1, 1:]) == q + v, (scene, integrator)


@pytest.mark.parametrize("mapping", ["", "seed", "exact", "calibrated", "compensated"])
@pytest.mark.parametrize("scene", SCENES)
def test_generate_text(scene, mapping):
    args = ["--mapping", mapping] if mapping else []
    out, _ = run_program("generate", scene, *args)
    assert contact2d.generate(contact2d.Scene.load(scene), mapping=mapping) == out


def test_generate_options():
    scene = "validation/scenes/box.toml"
    out, _ = run_program("generate", scene, "--geometry", "boxes", "--model-dt", "1e-3",
                         "--set", "contact.k=1e5")
    s = contact2d.Scene.load(scene, set=["contact.k=1e5"])
    assert contact2d.generate(s, geometry="boxes", model_dt=1e-3) == out


SOLREF_CASES = [
    (["--k", "2e4", "--c", "50", "--dt", "2e-3", "--mass", "1.5"],
     dict(k=2e4, c=50, dt=2e-3, mass=1.5)),
    (["--k", "1e5", "--c", "20", "--dt", "1e-3", "--mass", "2", "--joint", "hinge",
      "--inertia", "0.1", "--lever", "0.3", "--pivot", "0.5", "--mapping", "exact"],
     dict(k=1e5, c=20, dt=1e-3, mass=2, joint="hinge", inertia=0.1, lever=0.3, pivot=0.5,
          mapping="exact")),
    (["--restitution", "0.5", "--contact-time", "0.01", "--dt", "1e-3", "--mass", "1",
      "--mu", "0.8", "--contacts", "4"],
     dict(restitution=0.5, contact_time=0.01, dt=1e-3, mass=1, mu=0.8, contacts=4)),
    (["--k", "2e4", "--c", "50", "--dt", "2e-3", "--model", "docs/examples/box_on_plane.xml",
      "--body", "box"],
     dict(k=2e4, c=50, dt=2e-3, model="docs/examples/box_on_plane.xml", body="box")),
    (["--k", "2e4", "--c", "50", "--dt", "2e-3", "--model", "docs/examples/box_on_plane.xml",
      "--body", "box", "--engine", "mujoco3", "--settle", "1"],
     dict(k=2e4, c=50, dt=2e-3, model="docs/examples/box_on_plane.xml", body="box",
          engine="mujoco3", settle=1)),
    (["--k", "2e4", "--c", "50", "--dt", "2e-3", "--mass", "1.5", "--mu", "0.5", "--slope", "10"],
     dict(k=2e4, c=50, dt=2e-3, mass=1.5, mu=0.5, slope=10)),
]


@pytest.mark.parametrize("args,kwargs", SOLREF_CASES)
def test_solref_json(args, kwargs):
    out, err = run_program("solref", *args, "--json")
    with warnings.catch_warnings(record=True) as notes:
        warnings.simplefilter("always")
        assert contact2d.solref(**kwargs) == python_json(out)
    # The program's notes on stderr are Contact2dNote warnings, in Python's words.
    expected = [contact2d._python_words(line[len("contact2d: note: "):])
                for line in err.splitlines() if line.startswith("contact2d: note: ")]
    assert [str(n.message) for n in notes if n.category is contact2d.Contact2dNote] == expected


@pytest.mark.parametrize("args,kwargs", [
    (["docs/examples/inspect.xml", "--slope", "10"],
     dict(path="docs/examples/inspect.xml", slope=10)),
    (["docs/examples/box_on_plane.xml", "--pairs"],
     dict(path="docs/examples/box_on_plane.xml", pairs=True)),
    (["docs/examples/box_on_plane.xml", "--settle", "2", "--engine", "mujoco3"],
     dict(path="docs/examples/box_on_plane.xml", settle=2, engine="mujoco3")),
    (["docs/examples/inspect.xml", "--estimate-loads"],
     dict(path="docs/examples/inspect.xml", estimate_loads=True)),
])
def test_inspect_json(args, kwargs):
    out, _ = run_program("inspect", *args, "--json")
    assert contact2d.inspect(**kwargs) == python_json(out)


def test_mujoco3_is_the_programs(tmp_path):
    """engine="mujoco3" with friction="damper" is --engine mujoco3 --friction
    damper: the same trajectory, and generate(engine="mujoco3") the same MJCF."""
    scene = "validation/scenes/point_mass.toml"
    csv = tmp_path / "mj3.csv"
    run_program("simulate", scene, "--engine", "mujoco3", "--mapping", "compensated",
                "--friction", "damper", "--duration", "0.5", "--csv", str(csv))
    run = contact2d.simulate(contact2d.Scene.load(scene), engine="mujoco3",
                             mapping="compensated", friction="damper", duration=0.5)
    assert run.engine == "mujoco3:compensated::damper"  # the name with its options
    _, rows = read_csv(csv)
    assert csv_rows(run.trajectory) == rows
    out, _ = run_program("generate", scene, "--engine", "mujoco3", "--mapping", "compensated",
                         "--friction", "damper")
    assert contact2d.generate(contact2d.Scene.load(scene), mapping="compensated",
                              engine="mujoco3", friction="damper") == out
    with pytest.raises(ValueError, match=r'^friction damper: only over mapping="compensated" \('):
        contact2d.simulate(contact2d.Scene.load(scene), engine="mujoco3", friction="damper")
