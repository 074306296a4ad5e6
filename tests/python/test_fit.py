"""contact2d.fit: the program's numbers, with the per-impact arrays.

A recording of the first 24 shipped ellipse impacts (a few are flagged and
left out), no engines and no bootstrap so that it runs in about a second:
the module's JSON is the program's (the wall time excepted), and each
model's median is the median of its own per-impact errors, which are the
metric of its predicted and measured arrays."""

import json
import shutil

import numpy as np
import pytest

import contact2d
from conftest import SOURCE_DIR, run_program


@pytest.fixture
def recording(tmp_path):
    source = SOURCE_DIR / "validation/real/ellipse"
    shutil.copy(source / "recording.toml", tmp_path / "recording.toml")
    lines = (source / "impacts.csv").read_text().splitlines()[:25]
    (tmp_path / "impacts.csv").write_text("\n".join(lines) + "\n")
    return tmp_path / "recording.toml"


def without_time(data):
    return {k: v for k, v in data.items() if k not in ("seconds", "recording")}


def test_same_numbers_as_the_program(recording):
    out, _ = run_program("fit", str(recording), "--json", "--quiet", "--engines", "",
                         "--bootstrap", "0")
    result = contact2d.fit(recording, bootstrap=0, engines=[])
    assert without_time(result.json) == without_time(json.loads(out))


def test_arrays_give_the_figures(recording):
    result = contact2d.fit(recording, bootstrap=0, engines=[], k_profile=False)
    assert len(result.models) == 10  # 5 models × 2 splits
    body = result.json
    weight = np.sqrt(body["inertia"] / body["mass"])
    for m in result.models:
        n = len(m.impacts)
        assert m.errors.shape == (n,) and m.predicted.shape == (n, 3) and m.measured.shape == (n, 3)
        assert m.median == pytest.approx(float(np.median(m.errors)), rel=1e-12, abs=1e-15)
        w = np.array([1.0, 1.0, weight])
        expected = np.linalg.norm((m.predicted - m.measured) * w, axis=1) / np.linalg.norm(
            m.measured * w, axis=1)
        np.testing.assert_allclose(m.errors, expected, rtol=1e-12)
    penalty = result.model("penalty", "ref", "seeded")
    assert set(penalty.parameters) == {"k", "zeta", "c", "mu", "mu_roll"}
    with pytest.raises(KeyError):
        result.model("penalty", "no_such_engine")


def test_bad_arguments(recording):
    with pytest.raises(ValueError, match="bootstrap"):
        contact2d.fit(recording, bootstrap=-1)
    with pytest.raises(TypeError, match="engines"):
        contact2d.fit(recording, engines="mujoco")
    with pytest.raises(TypeError, match="recording"):
        contact2d.fit(3)
