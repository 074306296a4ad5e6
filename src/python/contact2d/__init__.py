"""contact2d from Python: the reference solver, MuJoCo beside it, and the
numbers for your own MuJoCo contact (docs/python.md).

The compiled extension ``_contact2d`` calls the same library functions as
the ``contact2d`` program, so every number is the program's to the bit.
What the program prints with ``--json`` arrives here as that same JSON,
parsed into a dict; trajectories are numpy arrays with the columns of
``COLUMNS`` (t, x, y, theta, vx, vy, omega).

Errors are exceptions carrying the program's one-line message: ValueError
for bad input, FileNotFoundError for a missing file, RuntimeError when a
run diverged or is not physics. Notes the program prints on stderr
(MuJoCo's warnings while loading a model, the refsafe note of generate)
are issued as Python warnings (``Contact2dNote``).
"""

import json as _json
import numbers as _numbers
import os as _os
import re as _re
import shlex as _shlex
import typing as _t
import warnings as _warnings
from dataclasses import dataclass as _dataclass, field as _field

import numpy as _np

from ._contact2d import BoxPart, Contact, Scene, Sim, State, mujoco_available
from ._contact2d import __version__
from . import _contact2d

__all__ = [
    "BoxPart", "COLUMNS", "Cancelled", "Contact", "Contact2dNote", "Fit", "FitModel", "Scene",
    "Sim", "Simulation", "State", "__version__", "compare", "fit", "generate", "inspect",
    "mujoco_available", "simulate", "solref",
]

_SceneLike = _t.Union[Scene, str, _os.PathLike]

# The command line's options as this module's keywords: the one table by
# which every message, warning, note and hint the libraries write in the
# program's words ("--mass 1: not with --model", "Try --dt 0.0031") reaches
# Python in its own ("mass=1: not with model=", "Try dt=0.0031"), and by
# which a diagnosis's fix becomes keywords (fix_kwargs). Each option: its
# keyword and what follows it, "number" (dt=0.0031), "word" (a name or a
# path: mapping="compensated"), "set" (--set KEY=VALUE: set=["KEY=VALUE"]),
# or, for a switch, the keyword's value (--no-diagnosis: diagnosis=False).
_FLAGS = {
    "--engine": ("engine", "word"), "--engines": ("engines", "word"),
    "--integrator": ("integrator", "word"), "--dt": ("dt", "number"),
    "--duration": ("duration", "number"), "--mapping": ("mapping", "word"),
    "--geometry": ("geometry", "word"), "--model-dt": ("model_dt", "number"),
    "--friction": ("friction", "word"), "--set": ("set", "set"),
    "--converged-tol": ("converged_tol", "number"),
    "--allow-nonphysical": ("allow_nonphysical", True),
    "--no-diagnosis": ("diagnosis", False), "--full-diagnosis": ("diagnosis", "full"),
    "--k": ("k", "number"), "--c": ("c", "number"), "--restitution": ("restitution", "number"),
    "--contact-time": ("contact_time", "number"), "--penetration": ("penetration", "number"),
    "--mass": ("mass", "number"), "--joint": ("joint", "word"), "--inertia": ("inertia", "number"),
    "--lever": ("lever", "number"), "--pivot": ("pivot", "number"), "--model": ("model", "word"),
    "--body": ("body", "word"), "--mu": ("mu", "number"), "--mu-roll": ("mu_roll", "number"),
    "--contacts": ("contacts", "number"), "--settle": ("settle", "number"),
    "--key": ("key", "word"), "--apply": ("apply", "word"), "--slope": ("slope", "number"),
    "--pairs": ("pairs", True), "--estimate-loads": ("estimate_loads", True),
    "--no-rest-search": ("rest_search", False), "--seed": ("seed", "number"),
    "--bootstrap": ("bootstrap", "number"), "--threads": ("threads", "number"),
    "--all-impacts": ("all_impacts", True), "--no-k-profile": ("k_profile", False),
}
_KINDS = ("number", "word", "set")  # any other kind is a switch's value
# An option and what may follow it: a token that does not end a sentence.
_OPTION = _re.compile(r"(?<![\w-])(--[a-z][a-z0-9-]*)(?: ([^\s:;,()`'\"]*[^\s:;,()`'\".]))?")
_NUMBER = _re.compile(r"[-+]?(?:(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|nan|inf)")
_PLACEHOLDER = _re.compile(r"[A-Z][A-Z_]*")  # --model FILE, --settle SECONDS
# Words after a --word option that are the sentence's, not its value.
_PROSE = {"a", "an", "the", "or", "and", "with", "to", "is", "for", "only", "in", "of", "on",
          "without", "when", "as", "it", "its", "that", "lets", "lists", "needs", "must", "not",
          "wrote", "writes", "reads", "builds", "takes", "gives", "makes", "keeps", "brings",
          "inspects", "shrinks", "changes"}


def _literal(value):
    """A keyword's value as Python source: 0.0031, "compensated", ["a=1"], False."""
    if isinstance(value, str):
        return _json.dumps(value, ensure_ascii=False)
    if isinstance(value, list):
        return "[" + ", ".join(_literal(v) for v in value) + "]"
    return repr(value)


def _option_value(kind, token):
    """The value `token` gives an option of `kind`, or None if it is prose."""
    if token is None:
        return None
    if _PLACEHOLDER.fullmatch(token):
        return token  # shown as is: model=FILE
    if kind == "number":
        return token if _NUMBER.fullmatch(token) else None
    if kind == "word":
        return None if token in _PROSE else _literal(token)
    return _literal([token])  # set


# A command line quoted in a text: `contact2d generate --mapping compensated`.
_COMMAND = _re.compile(r"`contact2d (simulate|compare|generate|solref|inspect|fit)((?: [^`]*)?)`")


def _python_call(match):
    """A quoted command line as the call of this module that does it:
    `contact2d.generate(scene, mapping="compensated")`; as it was if one of
    its words has no keyword."""
    try:
        function, words = match.group(1), _shlex.split(match.group(2))
    except ValueError:  # an unbalanced quote: not a command line after all
        return match.group(0)
    arguments = ["scene"] if function in ("simulate", "compare", "generate") else []
    i = 0
    while i < len(words):
        if words[i] not in _FLAGS:
            return match.group(0)
        name, kind = _FLAGS[words[i]]
        if kind not in _KINDS:
            arguments.append(f"{name}={_literal(kind)}")
            i += 1
            continue
        if i + 1 == len(words):
            return match.group(0)
        value = words[i + 1]
        if kind != "number":
            value = _literal([value] if kind == "set" else value)
        arguments.append(f"{name}={value}")
        i += 2
    return f"`contact2d.{function}({', '.join(arguments)})`"


def _python_words(text):
    """`text` with each of the program's options (_FLAGS) as its keyword,
    and a quoted command line as the call that does it."""
    if "--" not in text:
        return text
    text = _COMMAND.sub(_python_call, text)

    def keyword(match):
        flag, token = match.group(1), match.group(2)
        if flag not in _FLAGS:
            return match.group(0)
        name, kind = _FLAGS[flag]
        if token is None and text[match.end():match.end() + 2] == "'s":
            return name  # "--model's <include>": the model's
        rest = "" if token is None else " " + token
        if kind not in _KINDS:  # a switch
            return f"{name}={_literal(kind)}{rest}"
        value = _option_value(kind, token)
        return f"{name}={value}" if value is not None else f"{name}={rest}"

    return _OPTION.sub(keyword, text)


def _translated(value, keep=()):
    """Every string of a result (dicts, lists) in Python's words, but the
    keys in `keep` (compare's "text": what the program prints)."""
    if isinstance(value, str):
        return _python_words(value)
    if isinstance(value, list):
        return [_translated(v) for v in value]
    if isinstance(value, dict):
        return {k: (v if k in keep else _translated(v)) for k, v in value.items()}
    return value


def _fix_kwargs(fix):
    """A diagnosis's fix, the program's options ("--set contact.mu=0",
    "--dt 0.0002 --model-dt 0.002"), as keywords of compare() and
    simulate(): {"set": ["contact.mu=0"]}, {"dt": 0.0002, "model_dt": 0.002}."""
    kwargs = {}
    try:
        tokens = _shlex.split(fix)
        i = 0
        while i < len(tokens):
            name, kind = _FLAGS[tokens[i]]
            if kind not in _KINDS:
                kwargs[name] = kind
                i += 1
                continue
            value = tokens[i + 1]
            if kind == "set":
                kwargs.setdefault("set", []).append(value)
            else:
                kwargs[name] = float(value) if kind == "number" else value
            i += 2
    except (KeyError, IndexError, ValueError):
        return None  # an option the table lacks: the fix stays text (tested not to happen)
    return kwargs


def _with_fixes(result):
    """compare()'s dict with each diagnosis's fix in Python: "fix" as the
    keywords' text (set=["contact.mu=0"]) and "fix_kwargs" as a dict that
    compare(scene, **fix_kwargs) applies (None when the cause has no fix)."""
    for key, findings in result.items():
        if not key.endswith("diagnosis") or not isinstance(findings, list):
            continue
        for finding in findings:
            fix = finding.get("fix", "")
            kwargs = _fix_kwargs(fix) if fix else None
            finding["fix_kwargs"] = kwargs
            if kwargs:
                finding["fix"] = ", ".join(f"{k}={_literal(v)}" for k, v in kwargs.items())
    return result


def _call(function, *args):
    """An extension's function; its error in Python's words, same type."""
    try:
        return function(*args)
    except (ValueError, OSError, RuntimeError) as error:
        text = str(error)
        words = _python_words(text)
        try:
            translated = type(error)(words) if words != text else None
        except TypeError:  # an exception type that takes more than its text
            translated = None
        if translated is None:
            raise
        raise translated.with_traceback(error.__traceback__) from None


# Scene's attributes, in the scene file's terms: where each key of a
# "KEY=VALUE" assignment (set=, as --set) goes.
_BODY_KEYS = ("mass", "half_height", "width", "height", "radius", "a", "b", "inertia")


def _set_value(text):
    """A --set value read as the scene reader reads it: a TOML number, a
    boolean, a quoted string, else the bare word as a string."""
    if len(text) >= 2 and text[0] == text[-1] and text[0] in "\"'":
        return text[1:-1]
    if text in ("true", "false"):
        return text == "true"
    try:
        return int(text) if _re.fullmatch(r"[-+]?\d[\d_]*", text) else float(text)
    except ValueError:
        return text


def _apply_sets(scene, sets, function):
    """A copy of the scene with the assignments "KEY=VALUE" of set= made,
    as --set makes them on the scene file; the scene itself is unchanged."""
    if sets is None or len(sets) == 0:
        return scene
    if isinstance(sets, str):
        raise TypeError(f"{function}(): set must be a list of \"KEY=VALUE\" strings, e.g. "
                        f"[\"contact.mu=0\"], not a str")
    original, scene = scene, scene.copy()
    for assignment in sets:
        given = _literal([assignment])
        if not isinstance(assignment, str):
            raise TypeError(f"{function}(): set={given}: each must be a \"KEY=VALUE\" string")
        key, equals, text = assignment.partition("=")
        section, dot, name = key.strip().partition(".")
        if not equals or not text.strip():
            raise ValueError(f"{function}(): set={given}: expected KEY=VALUE, e.g. contact.k=1e6")
        if section == "scene" and not dot:
            target, name = scene, "shape"
        elif section == "body" and name in _BODY_KEYS:
            target = scene
        elif section in ("contact", "initial", "sim") and \
                isinstance(getattr(type(getattr(scene, section)), name, None), property):
            target = getattr(scene, section)
        else:
            raise ValueError(f"{function}(): set={given}: {key.strip()} is not a key set= can "
                             "change (scene, body.*, contact.*, initial.*, sim.*: docs/scenes.md)")
        try:
            setattr(target, name, _set_value(text.strip()))
        except TypeError as error:
            raise ValueError(f"{function}(): set={given}: {error}") from None
    try:
        original.validate()
    except ValueError:
        return scene  # the scene's own error, which the run raises
    try:
        scene.validate()  # a value out of range is set='s, not the file's
    except ValueError as error:
        text = str(error)
        prefix = (getattr(original, "source", "") or "scene") + ": "
        raise ValueError(f"{function}(): set={_literal(list(sets))}: "
                         f"{text[len(prefix):] if text.startswith(prefix) else text}") from None
    return scene


def _scene(scene, function):
    """A Scene, or the Scene a scene file path loads (as Scene.load)."""
    if isinstance(scene, Scene):
        return scene
    if isinstance(scene, (str, _os.PathLike)):
        return Scene.load(_os.fspath(scene))
    raise TypeError(f"{function}(): scene must be a contact2d.Scene or the path of a scene "
                    f"file, not {type(scene).__name__}")


def _number(value, name, function, unit):
    """None or a real number (not a bool, not a string), as a float."""
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, _numbers.Real):
        raise TypeError(f"{function}(): {name} must be a number ({unit}), not "
                        f"{type(value).__name__} {value!r}")
    return float(value)

COLUMNS = ("t", "x", "y", "theta", "vx", "vy", "omega")


class Contact2dNote(UserWarning):
    """A note the program prints on stderr ("contact2d: note: ...")."""


class Cancelled(RuntimeError):
    """A call ended by Ctrl-C (or another signal the main thread's handler
    raised on) while it ran on another thread: Python delivers the signal
    to the main thread, whose own call raises KeyboardInterrupt, and every
    contact2d call in progress is ended with it, its work dropped."""


def _notes(lines):
    for line in lines:
        _warnings.warn(_python_words(line), Contact2dNote, stacklevel=3)


@_dataclass
class Simulation:
    """One engine's run of a scene (``simulate``)."""

    trajectory: _np.ndarray  # one row per sample, columns COLUMNS
    warnings: _t.List[str]  # what the engine warned about; a kept non-physical run
    notes: _t.List[str]  # facts that are not failures, e.g. "refsafe"
    engine: str  # the engine's name ("ref", "mujoco:calibrated")
    description: str  # e.g. "mujoco calibrated Euler"
    seconds: float  # wall clock of the run loop
    summary: str  # the line `contact2d simulate` prints
    columns: tuple = _field(default=COLUMNS)

    def column(self, name: str) -> _np.ndarray:
        """One column of the trajectory by name ("t", "x", ..., "omega")."""
        return self.trajectory[:, self.columns.index(name)]


def simulate(scene: _SceneLike, engine: str = "ref", integrator: _t.Optional[str] = None,
             dt: _t.Optional[float] = None, duration: _t.Optional[float] = None,
             mapping: _t.Optional[str] = None, geometry: _t.Optional[str] = None,
             model_dt: _t.Optional[float] = None, allow_nonphysical: bool = False,
             friction: _t.Optional[str] = None,
             set: _t.Optional[_t.Sequence[str]] = None) -> Simulation:
    """Runs one engine on the scene, as ``contact2d simulate``.

    scene: a Scene, or the path of a scene file (docs/scenes.md).
    engine: "ref" (the reference solver), "mujoco" (MuJoCo 2.2.2) or
        "mujoco3" (MuJoCo 3.14, docs/mujoco3.md).
    integrator: "explicit_euler", "semi_implicit_euler", "implicit_euler" or
        "rk4"; None keeps the scene's. MuJoCo runs them as Euler, implicit, RK4.
    dt, duration: the time step and the simulated time, in seconds; None
        keeps the scene's.
    mapping, geometry: MuJoCo's model (seed, exact, calibrated or
        compensated; corners or boxes); None: MuJoCo's defaults, calibrated
        and corners (the engine's own options, e.g. "mujoco:exact", else).
    model_dt: the Δt MuJoCo's Δt-dependent model values are computed for
        (``--model-dt``), in (0, 1] s; None: the time step.
    allow_nonphysical: keep a run that is not physics (its reason then is in
        ``warnings``) instead of raising RuntimeError.
    friction: MuJoCo 3's "shared" or "damper"; None: shared.
    set: assignments "KEY=VALUE" made on a copy of the scene, as the
        program's --set makes them on the file (["contact.mu=0"]); None: none.

    Returns a Simulation: the trajectory (one row per sample, columns
    COLUMNS: s, m, m, rad, m/s, m/s, rad/s), warnings, notes and the summary
    line. Raises ValueError for bad input, FileNotFoundError for a missing
    scene file, RuntimeError when the run diverged or is not physics, and
    KeyboardInterrupt on Ctrl-C.
    """
    run = _call(_contact2d._simulate, _apply_sets(_scene(scene, "simulate"), set, "simulate"),
                engine, integrator, _number(dt, "dt", "simulate", "s"),
                _number(duration, "duration", "simulate", "s"), mapping or "", geometry or "",
                friction or "", _number(model_dt, "model_dt", "simulate", "s"),
                allow_nonphysical)
    run["warnings"] = _translated(run["warnings"])
    run["notes"] = _translated(run["notes"])
    return Simulation(**run)


def compare(scene: _SceneLike, mapping: _t.Optional[str] = None,
            geometry: _t.Optional[str] = None, model_dt: _t.Optional[float] = None,
            integrator: _t.Optional[str] = None, dt: _t.Optional[float] = None,
            duration: _t.Optional[float] = None, converged_tol: float = 1e-12,
            diagnosis: _t.Union[bool, str] = True, allow_nonphysical: bool = False,
            engines: _t.Sequence[str] = (), friction: _t.Optional[str] = None,
            set: _t.Optional[_t.Sequence[str]] = None) -> dict:
    """The reference and MuJoCo against the converged solution and each
    other, as ``contact2d compare --json``: that JSON object as a dict, with
    the trajectories added as arrays ("ref_trajectory", "mujoco_trajectory",
    "converged_trajectory": the converged solution at the reference's sample
    times, None where it is not available), "warnings", and "text": the
    table and diagnosis `contact2d compare` prints. ``engines``, as
    ``--engines``, compares the reference with each engine of the list
    (names with their options, "mujoco:exact:boxes"; not together with
    mapping or geometry): every engine adds its keys and its
    "KEY_trajectory" ("mujoco_exact_trajectory" when two share a kind).
    ``diagnosis``: True (the default) re-runs without each cause, the ones
    at a smaller step only when the others leave the difference
    unexplained; "full" makes those too (``--full-diagnosis``); False skips
    the diagnosis (``--no-diagnosis``). Each cause in "diagnosis" has its
    "fix" as keywords ('set=["contact.mu=0"]', "dt=0.0002") and as a dict,
    "fix_kwargs", that ``compare(scene, **fix_kwargs)`` applies. mapping,
    geometry, friction, model_dt, integrator, dt, duration and set: as for
    simulate (None: not given)."""
    if isinstance(diagnosis, str) and diagnosis != "full":
        raise ValueError(f"compare(): diagnosis={diagnosis!r}: must be True, False or \"full\"")
    if not isinstance(diagnosis, (bool, str)):
        raise TypeError(f"compare(): diagnosis must be True, False or \"full\", "
                        f"not {type(diagnosis).__name__}")
    run = _call(_contact2d._compare, _apply_sets(_scene(scene, "compare"), set, "compare"),
                integrator, _number(dt, "dt", "compare", "s"),
                _number(duration, "duration", "compare", "s"), mapping or "", geometry or "",
                friction or "", _number(model_dt, "model_dt", "compare", "s"), list(engines),
                _number(converged_tol, "converged_tol", "compare", "m"),
                diagnosis is not False, diagnosis == "full", allow_nonphysical)
    result = _translated(_with_fixes(_json.loads(run["json"])))
    for key, value in run.items():
        if key != "json":
            result[key] = _translated(value) if key == "warnings" else value
    return result


def generate(scene: _SceneLike, mapping: _t.Optional[str] = None,
             geometry: _t.Optional[str] = None, model_dt: _t.Optional[float] = None,
             integrator: _t.Optional[str] = None, dt: _t.Optional[float] = None,
             duration: _t.Optional[float] = None, engine: str = "mujoco",
             friction: _t.Optional[str] = None, set: _t.Optional[_t.Sequence[str]] = None) -> str:
    """The MuJoCo MJCF of the scene, as ``contact2d generate``: for MuJoCo
    2.2.2 (engine "mujoco") or MuJoCo 3 ("mujoco3", with friction "damper"
    if asked; not checked by MuJoCo 3 here, the engine loads it). The other
    keywords: as for simulate (None: not given)."""
    run = _call(_contact2d._generate, _apply_sets(_scene(scene, "generate"), set, "generate"),
                integrator, _number(dt, "dt", "generate", "s"),
                _number(duration, "duration", "generate", "s"), mapping or "", geometry or "",
                friction or "", engine, _number(model_dt, "model_dt", "generate", "s"))
    _notes(run["notes"])
    return run["xml"]


def _required(value, name, function, unit):
    """A number that has no "absent": None is a TypeError naming the keyword."""
    if value is None:
        raise TypeError(f"{function}(): {name} must be a number ({unit}), not None")
    return value


def _path(value, name, function, optional=False):
    """A path given as str or os.PathLike, as str; None is "" when optional."""
    if optional and value is None:
        return ""
    if isinstance(value, (str, _os.PathLike)):
        path = _os.fspath(value)
        if "\0" in path:  # the C library would stop the path there
            raise ValueError(f"{function}(): {name} has a NUL character, which no file "
                             "name can hold")
        return path
    raise TypeError(f"{function}(): {name} must be a path (str or os.PathLike"
                    f"{', or None' if optional else ''}), not {type(value).__name__}")


def solref(k: _t.Optional[float] = None, c: _t.Optional[float] = None, *,
           dt: _t.Optional[float] = None,
           mass: _t.Optional[float] = None, mapping: str = "all", joint: _t.Optional[str] = None,
           inertia: float = 0.0, lever: float = 0.0, pivot: float = 0.0,
           mu: _t.Optional[float] = None, mu_roll: float = 0.0,
           model: _t.Union[str, _os.PathLike, None] = None, body: _t.Optional[str] = None,
           contacts: _t.Optional[int] = None, restitution: _t.Optional[float] = None,
           contact_time: _t.Optional[float] = None,
           penetration: _t.Optional[float] = None, engine: str = "mujoco", settle: float = 3.0,
           key: _t.Optional[str] = None, apply: _t.Union[str, _os.PathLike, None] = None,
           slope: _t.Optional[float] = None) -> dict:
    """solref, solimp, impratio and what MuJoCo does with them, per mapping,
    as ``contact2d solref --json`` (docs/cli.md): that JSON object as a dict.

    Each keyword is the option of the same name, in its unit: ``k`` N/m and
    ``c`` N·s/m per MuJoCo contact; ``dt`` s (MuJoCo's timestep; with
    ``model`` it defaults to the model's own, else it is required);
    ``mass`` kg; ``inertia`` kg·m²; ``lever`` and ``pivot`` m; ``mu``
    (dimensionless) and ``mu_roll`` m; ``restitution`` in (0, 1);
    ``contact_time`` s; ``penetration`` m (a static depth per contact);
    ``contacts`` a count; ``settle`` s; ``slope`` degrees in [0, 90).
    ``joint``: "free", "planar", "slide" or "hinge"; ``mapping``: a mapping
    or "all". ``model`` (an MJCF path) reads the body ``body`` from a model;
    ``apply`` (a path) writes that model with the recommendation; ``key``
    starts ``model`` from a keyframe. None: not given (no model, its first
    body, no file written, qpos0). ``engine`` is ``"mujoco"`` for 2.2.2 or
    ``"mujoco3"`` for 3.14. Errors name these keywords (``mass=2: not with
    model=``), not the program's options."""
    def number(value, name, unit):
        return _number(value, name, "solref", unit)
    run = _call(_contact2d._solref, number(k, "k", "N/m"), number(c, "c", "N·s/m"),
                number(dt, "dt", "s"), number(mass, "mass", "kg"), mapping, joint,
                number(inertia, "inertia", "kg·m²"), number(lever, "lever", "m"),
                number(pivot, "pivot", "m"), number(mu, "mu", "dimensionless"),
                number(mu_roll, "mu_roll", "m"),
                _path(model, "model", "solref", True), body or "", contacts,
                number(restitution, "restitution", "dimensionless"),
                number(contact_time, "contact_time", "s"),
                number(penetration, "penetration", "m"), engine,
                _required(number(settle, "settle", "s"), "settle", "solref", "s"),
                key or "",
                _path(apply, "apply", "solref", True),
                number(slope, "slope", "degrees"))
    _notes(run["notes"])
    return _translated(_json.loads(run["json"]))


def inspect(path: _t.Union[str, _os.PathLike], key: _t.Optional[str] = None, pairs: bool = False,
            slope: _t.Optional[float] = None, settle: float = 0.0, estimate_loads: bool = False,
            engine: str = "mujoco", rest_search: bool = True) -> dict:
    """Any MJCF model's contacts in physical units, as
    ``contact2d inspect --json`` (docs/inspect.md): that JSON object as a
    dict. ``path``: the MJCF file (str or os.PathLike); ``key``: the
    keyframe to start from (None: qpos0); ``settle``: seconds MuJoCo steps
    the model first, so it comes to rest on what it touches; ``slope``:
    degrees in [0, 90), each contact's creep speed under friction;
    ``pairs``: every geom pair's distance; ``estimate_loads``: loads from a
    body's weight where MuJoCo has none; ``engine``: ``"mujoco"`` for 2.2.2
    or ``"mujoco3"`` for 3.14; ``rest_search``: when the model is not at
    rest, settle it longer to say how long it takes (``--no-rest-search``
    is ``rest_search=False``)."""
    run = _call(_contact2d._inspect, _path(path, "path", "inspect"), key or "", pairs,
                              _number(slope, "slope", "inspect", "degrees"),
                              _required(_number(settle, "settle", "inspect", "s"), "settle",
                                        "inspect", "s"), estimate_loads, engine,
                              bool(rest_search))
    _notes(run["notes"])
    return _translated(_json.loads(run["json"]))


@_dataclass
class FitModel:
    """One model of a fit on one split, measured on the split's held-out
    impacts (docs/real-impacts.md). ``parameters`` and ``spread`` (the
    bootstrap's 16th and 84th percentiles, for the reference's penalty fit)
    as dicts; per held-out impact, as numpy arrays: ``impacts`` (the
    recording's ids), ``errors`` (‖W(v̂ − v)‖/‖W v‖), ``predicted`` and
    ``measured`` ((n, 3): vx, vy, omega after the impact)."""
    name: str
    engine: str
    split: str
    median: float
    iqr: float
    parameters: dict
    spread: dict
    impacts: _np.ndarray
    errors: _np.ndarray
    predicted: _np.ndarray
    measured: _np.ndarray


@_dataclass
class Fit:
    """What ``contact2d fit --json`` prints, as ``json`` (a dict), and its
    models with their per-impact arrays, as ``models`` (FitModel)."""
    json: dict
    models: _t.List[FitModel]

    def model(self, name: str = "penalty", engine: str = "ref", split: str = "seeded") -> FitModel:
        """The one model of that name, engine and split."""
        for m in self.models:
            if (m.name, m.engine, m.split) == (name, engine, split):
                return m
        raise KeyError(f"fit: no model {name!r} on engine {engine!r}, split {split!r}")


def fit(recording: _t.Union[str, _os.PathLike], seed: int = 2026, bootstrap: int = 8,
        engines: _t.Optional[_t.Sequence[str]] = None, threads: int = 0, all_impacts: bool = False,
        k_profile: bool = True) -> Fit:
    """k, c, mu and mu_roll fitted to a recording of real impacts, and every
    model measured on held-out impacts, as ``contact2d fit`` (docs/real-impacts.md;
    the format: docs/recordings.md). ``recording``: the manifest (str or
    os.PathLike); ``seed``: the seeded split's shuffle; ``bootstrap``: refits
    for the parameters' spread (0: none); ``engines``: the engines that
    replay the held-out impacts with the fitted parameters (None: every
    built-in engine with soft constraints, MuJoCo 2.2.2 and 3.14; []: none);
    ``threads``: 0 for one per core; ``all_impacts``: keep the impacts the
    recording flags; ``k_profile``: the seeded split's profile of k."""
    if isinstance(seed, bool) or not isinstance(seed, _numbers.Integral) or not 0 <= seed < 2**53:
        raise ValueError(f"fit(): seed = {seed!r}: an integer in [0, 2**53)")
    if isinstance(bootstrap, bool) or not isinstance(bootstrap, _numbers.Integral) \
            or not 0 <= bootstrap <= 1000:
        raise ValueError(f"fit(): bootstrap = {bootstrap!r}: an integer in [0, 1000]")
    if isinstance(threads, bool) or not isinstance(threads, _numbers.Integral) \
            or not 0 <= threads <= 256:
        raise ValueError(f"fit(): threads = {threads!r}: an integer in [0, 256] (0: one per core)")
    if engines is not None:
        if isinstance(engines, str):
            raise TypeError("fit(): engines must be a list of engine names, e.g. ['mujoco'], "
                            "not a string")
        engines = [str(e) for e in engines]
    run = _call(_contact2d._fit, _path(recording, "recording", "fit"), int(seed), int(bootstrap),
                engines, int(threads), bool(all_impacts), bool(k_profile))
    data = _translated(_json.loads(run["json"]))
    models = []
    for entry, arrays in zip(data["models"], run["arrays"]):
        models.append(FitModel(
            name=entry["name"], engine=entry["engine"], split=entry["split"],
            median=entry["median"], iqr=entry["iqr"], parameters=dict(entry["parameters"]),
            spread={k: tuple(v) for k, v in entry.get("spread_16_84", {}).items()},
            impacts=arrays["impacts"], errors=arrays["errors"], predicted=arrays["predicted"],
            measured=arrays["measured"]))
    return Fit(json=data, models=models)


# Scene.load's errors in Python's words, as every function's.
_load = Scene.load


def _scene_load(path, set=()):
    if isinstance(set, str):
        raise TypeError("Scene.load(): set must be a list of \"KEY=VALUE\" strings, e.g. "
                        "[\"contact.k=1e5\"], not a str")
    return _call(_load, path, list(set))


_scene_load.__doc__ = """Scene.load(path, set=()): the scene of a TOML scene file (str or
os.PathLike), with the assignments "KEY=VALUE" of ``set`` made as the
program's --set makes them (["contact.k=1e5"]; docs/scenes.md). Raises
FileNotFoundError for a missing file, ValueError for a bad value."""
_scene_load.__name__, _scene_load.__qualname__ = "load", "Scene.load"
Scene.load = staticmethod(_scene_load)


def _repr(self):
    """Scene, Contact, State, Sim, BoxPart as a dataclass shows itself:
    every field with its value (Contact(k=10000.0, c=20.0, ...))."""
    cls = type(self)
    names = [name for name, value in vars(cls).items()
             if isinstance(value, property) and not name.startswith("_")]
    fields = [f"{name}={getattr(self, name)!r}" for name in names]
    if "source" in getattr(self, "__dict__", {}):
        fields.append(f"source={self.source!r}")
    return f"{cls.__name__}({', '.join(fields)})"


for _class in (BoxPart, Contact, State, Sim, Scene):
    _class.__repr__ = _repr
del _class
