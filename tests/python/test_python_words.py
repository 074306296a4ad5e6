"""Python speaks Python, not the command line (issue 51 §1): errors and
hints name the keyword (mass=, settle=, dt=0.0031), not the option; a
diagnosis's fix is keywords, with a dict compare() applies; a wrong type
for a scene field says the field and what it takes; the objects show
their values; dir(contact2d) is the public names; no default is a
meaningless ''."""

import inspect

import numpy as np
import pytest

import contact2d
from conftest import program_error

BOX = "validation/scenes/box.toml"
CIRCLE = "validation/scenes/circle.toml"
MODEL = "docs/examples/box_on_plane.xml"
INSPECT = "docs/examples/inspect.xml"

# Each public function provoked, with the start of its message in the
# program's words (checked against the program where it says the same)
# and in Python's.
ERRORS = [
    ("solref", lambda: contact2d.solref(k=1e4, c=1, dt=1e-3, mass=2, model=MODEL, body="box"),
     ValueError, "--mass 2: not with --model", "mass=2: not with model= "),
    ("solref", lambda: contact2d.solref(k=1e4, c=1, dt=1e-3),
     ValueError, "missing --mass, or --model FILE --body NAME",
     "missing mass=, or model=FILE body=NAME"),
    ("solref", lambda: contact2d.solref(k=1e4, c=1, dt=1e-3, mass=1, mu_roll=-1),
     ValueError, "--mu-roll -1: ", "mu_roll=-1: must be a finite number >= 0 (m)"),
    ("solref", lambda: contact2d.solref(k=1e4, c=1, dt=1e-3, mass=1, engine="bullet"),
     ValueError, "--engine bullet: ", 'engine="bullet": '),
    ("solref", lambda: contact2d.solref(k=1e4, c=1, dt=1e-3, mass=1, apply="x.xml"),
     ValueError, "--apply x.xml: needs --model FILE --body NAME",
     'apply="x.xml": needs model=FILE body=NAME'),
    ("inspect", lambda: contact2d.inspect(INSPECT, settle=-1),
     ValueError, "--settle -1: ", "settle=-1: must be a time in seconds"),
    ("inspect", lambda: contact2d.inspect(INSPECT, slope=95),
     ValueError, "--slope 95: ", "slope=95: must be in [0, 90) degrees"),
    ("inspect", lambda: contact2d.inspect(INSPECT, key="nokey"),
     ValueError, "--key nokey: ", 'key="nokey": no keyframe of that name'),
    ("simulate", lambda: contact2d.simulate("tests/cli/bad_inputs/diverging_dt.toml",
                                            integrator="explicit_euler", dt=0.005),
     RuntimeError, "Try --dt 7.9e-05 or --integrator semi_implicit_euler.",
     'Try dt=7.9e-05 or integrator="semi_implicit_euler".'),
    ("Scene.load", lambda: contact2d.Scene.load(BOX, set=["contact.c=-1"]),
     ValueError, "--set contact.c=-1: ", 'set=["contact.c=-1"]: contact.c = -1 is out of range'),
    ("compare", lambda: contact2d.compare(BOX, set=["contact.c=-1"]),
     ValueError, None, 'compare(): set=["contact.c=-1"]: contact.c = -1 is out of range'),
    ("generate", lambda: contact2d.generate(BOX, set=["contact.k=abc"]),
     ValueError, None, 'generate(): set=["contact.k=abc"]: contact.k must be a number (N/m)'),
]
# The program's own line for the ones it says the same way (the program's
# option parser refuses --mass with --model before the library does).
PROGRAM = {
    "--settle -1: ": ("inspect", INSPECT, "--settle", "-1"),
    "--set contact.c=-1: ": ("simulate", BOX, "--set", "contact.c=-1"),
}


@pytest.mark.parametrize("function, call, kind, program, python", ERRORS,
                         ids=[f"{e[0]}-{i}" for i, e in enumerate(ERRORS)])
def test_errors_name_the_keyword(function, call, kind, program, python):
    with pytest.raises(kind) as e:
        call()
    message = str(e.value)
    assert python in message, message
    assert "--" not in message, message
    assert "\n" not in message
    if program in PROGRAM:  # the program says it with its options
        assert program_error(*PROGRAM[program]).startswith(program)


def test_every_option_in_the_table_is_a_keyword():
    """The one table (contact2d._FLAGS) names keywords that exist."""
    keywords = set()
    for name in ("simulate", "compare", "generate", "solref", "inspect", "fit"):
        keywords |= set(inspect.signature(getattr(contact2d, name)).parameters)
    for flag, (keyword, _) in contact2d._FLAGS.items():
        assert flag.startswith("--") and keyword in keywords, (flag, keyword)


def test_words_a_sentence_keeps():
    """A word after an option is its value only when it is not prose."""
    words = contact2d._python_words
    assert words("--mass or --model: one of them is required") == \
        "mass= or model=: one of them is required"
    assert words("Try a smaller --dt.") == "Try a smaller dt=."
    assert words("run with --settle 2.5 s") == "run with settle=2.5 s"
    assert words("(--joint slide)") == '(joint="slide")'
    assert words("--no-rest-search and --allow-nonphysical") == \
        "rest_search=False and allow_nonphysical=True"
    assert words("--unknown-option 3 stays") == "--unknown-option 3 stays"
    assert words("were not made; --full-diagnosis makes them.") == \
        'were not made; diagnosis="full" makes them.'
    assert words("(not a pair --apply wrote: ...)") == "(not a pair apply= wrote: ...)"
    assert words("--model's <include>") == "model's <include>"
    # An unbalanced quote is no command line: the options alone, no exception.
    assert words("`contact2d simulate --set 'a`") == "`contact2d simulate set= 'a`"
    # A quoted command line is the call that does it.
    assert words("which only `contact2d generate --engine mujoco3 --mapping compensated "
                 "--friction damper` builds") == \
        ('which only `contact2d.generate(scene, engine="mujoco3", mapping="compensated", '
         'friction="damper")` builds')
    assert words("`contact2d compare --dt 2e-4 --set contact.mu=0`") == \
        '`contact2d.compare(scene, dt=2e-4, set=["contact.mu=0"])`'


def test_fix_kwargs_of_each_kind():
    fix = contact2d._fix_kwargs
    assert fix("--set contact.mu=0 --set contact.mu_roll=0") == \
        {"set": ["contact.mu=0", "contact.mu_roll=0"]}
    assert fix("--dt 0.0002 --model-dt 0.002") == {"dt": 0.0002, "model_dt": 0.002}
    assert fix("--mapping compensated") == {"mapping": "compensated"}
    assert fix("--no-such-option 3") is None  # stays text: compare() does not fail on it
    for kwargs in (fix("--dt 0.0002 --model-dt 0.002"), fix("--set contact.mu=0")):
        inspect.signature(contact2d.compare).bind("scene", **kwargs)  # compare takes them


@pytest.mark.parametrize("scene, duration", [(CIRCLE, 1.5), (BOX, 0.6)])
def test_a_diagnosis_fix_applied_does_what_it_says(scene, duration):
    """Each named cause's fix_kwargs, given to compare, is the diagnosis's
    re-run without that cause: the engines' distance is its "after" (the
    same runs, so equal to the 10 digits --json prints)."""
    result = contact2d.compare(scene, duration=duration)
    findings = result["diagnosis"]
    assert findings, result["diagnosis_summary"]
    kinds = set()
    for finding in findings:
        kwargs = finding["fix_kwargs"]
        assert "--" not in finding["fix"] and "--" not in finding["explanation"]
        assert finding["fix"] == ", ".join(f"{k}={contact2d._literal(v)}"
                                           for k, v in kwargs.items())
        kinds |= set(kwargs)
        # converged_tol 1e-6: the engines' distance does not use the converged
        # solution, which at 1e-12 takes 53 s under the soft cone (0.2 s here).
        again = contact2d.compare(scene, duration=duration, diagnosis=False,
                                  converged_tol=1e-6, **kwargs)
        assert again["max_pos_err"] == pytest.approx(finding["after"], rel=1e-9, abs=0), finding
        assert again["max_pos_err"] < finding["before"]  # removing the cause helps
    if scene == CIRCLE:
        assert kinds == {"set", "mapping"}


def test_set_changes_a_copy():
    scene = contact2d.Scene.load(BOX)
    ran = contact2d.simulate(scene, duration=0.2, set=["contact.mu=0", "sim.integrator=rk4",
                                                       "initial.vx=2"])
    loaded = contact2d.Scene.load(BOX, set=["contact.mu=0", "sim.integrator=rk4",
                                            "initial.vx=2"])
    assert np.array_equal(ran.trajectory, contact2d.simulate(loaded, duration=0.2).trajectory)
    assert scene.contact.mu == 0.5 and scene.sim.integrator == "semi_implicit_euler"
    with pytest.raises(ValueError, match=r'^simulate\(\): set=\["contact.foo=1"\]: contact.foo '
                                         r'is not a key set= can change'):
        contact2d.simulate(scene, set=["contact.foo=1"])
    with pytest.raises(TypeError, match=r"set must be a list"):
        contact2d.simulate(scene, set="contact.mu=0")


@pytest.mark.parametrize("target, field, value, message", [
    ("contact", "k", "1e4", "contact.k must be a number (N/m), not str '1e4'"),
    ("contact", "damping", 5, 'contact.damping must be a string, "compression" or '
                              '"kelvin_voigt", not int 5'),
    ("sim", "dt", None, "sim.dt must be a number (s), not NoneType None"),
    ("sim", "integrator", 4, "sim.integrator must be a string, "),
    ("initial", "vx", True, "initial.vx must be a number (m/s), not bool True"),
    ("scene", "mass", "1", "body.mass must be a number (kg), not str '1'"),
    ("scene", "parts", [1], "body.parts[0] must be a contact2d.BoxPart, not int 1"),
    ("scene", "contact", 3, "contact must be a contact2d.Contact, not int 3"),
    ("scene", "shape", 2, 'shape must be a string, "point_mass", '),
])
def test_a_wrong_type_says_the_field(target, field, value, message):
    """pybind11 said "(): incompatible function arguments" and listed C++ types."""
    scene = contact2d.Scene.load(BOX)
    obj = scene if target == "scene" else getattr(scene, target)
    with pytest.raises(TypeError) as e:
        setattr(obj, field, value)
    assert str(e.value).startswith(message)
    assert "\n" not in str(e.value) and "incompatible" not in str(e.value)


def test_numbers_of_any_real_type_are_taken():
    scene = contact2d.Scene.load(BOX)
    scene.contact.k = np.float64(2e4)
    scene.contact.c = np.int64(7)
    scene.initial.vx = 3
    assert (scene.contact.k, scene.contact.c, scene.initial.vx) == (2e4, 7.0, 3.0)
    with pytest.raises(TypeError, match=r"^BoxPart\(\): y must be a number \(m\), not str"):
        contact2d.BoxPart(0.1, 0.1, 0, "0", 1)


def test_repr_shows_the_values():
    scene = contact2d.Scene.load(BOX)
    assert repr(scene.contact) == (
        "Contact(k=10000.0, c=50.0, mu=0.5, alpha=100.0, mu_roll=0.0, mu_torsion=0.0, "
        "cone_ratio=1.0, damping='compression', friction_law='tanh')")
    assert repr(scene.initial) == "State(x=0.0, y=0.6, theta=0.3, vx=1.0, vy=0.0, omega=0.0)"
    assert repr(scene.sim) == ("Sim(dt=0.0001, duration=2.0, output_dt=0.001, gravity=9.81, "
                               "integrator='semi_implicit_euler')")
    assert repr(contact2d.Scene("tshape").parts[0]) == \
        "BoxPart(width=0.6, height=0.1, x=0.0, y=0.25, mass=0.6)"
    assert repr(scene) == (
        "Scene(shape='box', mass=1.0, half_height=0.05, width=0.4, height=0.2, radius=0.1, "
        "a=0.2, b=0.1, inertia=0.0, parts=[], contact=" + repr(scene.contact) + ", initial=" +
        repr(scene.initial) + ", sim=" + repr(scene.sim) + f", obstacles=0, source={BOX!r})")
    assert "source=" not in repr(contact2d.Scene("box"))
    run = contact2d.simulate(scene, duration=0.01)
    assert repr(run).startswith("Simulation(trajectory=array([[") and "engine='ref'" in repr(run)
    for text in (repr(scene), repr(run)):
        assert " object at 0x" not in text


def test_dir_is_the_public_names():
    """dir(contact2d) listed np, os, json, Union, dataclass, ... beside the API."""
    public = sorted(n for n in dir(contact2d) if not n.startswith("_"))
    assert public == sorted(n for n in contact2d.__all__ if not n.startswith("_"))
    for name in contact2d.__all__:
        assert hasattr(contact2d, name), name


def test_no_default_is_an_empty_string():
    """help(compare) showed mapping: str = '': None now, its meaning in the docstring."""
    for name in ("simulate", "compare", "generate", "solref", "inspect", "fit"):
        function = getattr(contact2d, name)
        for parameter in inspect.signature(function).parameters.values():
            assert parameter.default != "", (name, parameter.name)
    assert inspect.signature(contact2d.compare).parameters["mapping"].default is None
    assert "None: MuJoCo's defaults, calibrated" in contact2d.simulate.__doc__
    assert "None: not given" in contact2d.compare.__doc__
    # None is "not given": the same MJCF as without the keyword.
    assert contact2d.generate(BOX, mapping=None, geometry=None) == contact2d.generate(BOX)
