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

import json
import numbers
import os
import warnings
from dataclasses import dataclass, field
from typing import List, Optional, Sequence, Union

import numpy as np

from ._contact2d import BoxPart, Contact, Scene, Sim, State, mujoco_available
from ._contact2d import __version__
from . import _contact2d

__all__ = [
    "BoxPart", "COLUMNS", "Cancelled", "Contact", "Contact2dNote", "Fit", "FitModel", "Scene",
    "Sim",
    "Simulation", "State", "__version__", "compare", "fit", "generate", "inspect",
    "mujoco_available", "simulate", "solref",
]

SceneLike = Union[Scene, str, os.PathLike]


def _scene(scene, function):
    """A Scene, or the Scene a scene file path loads (as Scene.load)."""
    if isinstance(scene, Scene):
        return scene
    if isinstance(scene, (str, os.PathLike)):
        return Scene.load(os.fspath(scene))
    raise TypeError(f"{function}(): scene must be a contact2d.Scene or the path of a scene "
                    f"file, not {type(scene).__name__}")


def _number(value, name, function, unit):
    """None or a real number (not a bool, not a string), as a float."""
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
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
        warnings.warn(line, Contact2dNote, stacklevel=3)


@dataclass
class Simulation:
    """One engine's run of a scene (``simulate``)."""

    trajectory: np.ndarray  # one row per sample, columns COLUMNS
    warnings: List[str]  # what the engine warned about; a kept non-physical run
    notes: List[str]  # facts that are not failures, e.g. "refsafe"
    engine: str  # the engine's name ("ref", "mujoco:calibrated")
    description: str  # e.g. "mujoco calibrated Euler"
    seconds: float  # wall clock of the run loop
    summary: str  # the line `contact2d simulate` prints
    columns: tuple = field(default=COLUMNS)

    def column(self, name: str) -> np.ndarray:
        """One column of the trajectory by name ("t", "x", ..., "omega")."""
        return self.trajectory[:, self.columns.index(name)]


def simulate(scene: SceneLike, engine: str = "ref", integrator: Optional[str] = None,
             dt: Optional[float] = None, duration: Optional[float] = None, mapping: str = "",
             geometry: str = "", model_dt: Optional[float] = None,
             allow_nonphysical: bool = False, friction: str = "") -> Simulation:
    """Runs one engine on the scene, as ``contact2d simulate``.

    scene: a Scene, or the path of a scene file (docs/scenes.md).
    engine: "ref" (the reference solver), "mujoco" (MuJoCo 2.2.2) or
        "mujoco3" (MuJoCo 3.14, docs/mujoco3.md).
    integrator: "explicit_euler", "semi_implicit_euler", "implicit_euler" or
        "rk4"; None keeps the scene's. MuJoCo runs them as Euler, implicit, RK4.
    dt, duration: the time step and the simulated time, in seconds; None
        keeps the scene's.
    mapping, geometry: MuJoCo's model (``--mapping``: seed, exact, calibrated,
        compensated; ``--geometry``: corners, boxes); "" is the default.
    model_dt: the Δt MuJoCo's Δt-dependent model values are computed for
        (``--model-dt``), in (0, 1] s; None: the time step.
    allow_nonphysical: keep a run that is not physics (its reason then is in
        ``warnings``) instead of raising RuntimeError.
    friction: MuJoCo 3's "shared" or "damper" (``--friction``).

    Returns a Simulation: the trajectory (one row per sample, columns
    COLUMNS: s, m, m, rad, m/s, m/s, rad/s), warnings, notes and the summary
    line. Raises ValueError for bad input, FileNotFoundError for a missing
    scene file, RuntimeError when the run diverged or is not physics, and
    KeyboardInterrupt on Ctrl-C.
    """
    run = _contact2d._simulate(_scene(scene, "simulate"), engine, integrator,
                               _number(dt, "dt", "simulate", "s"),
                               _number(duration, "duration", "simulate", "s"), mapping, geometry,
                               friction, _number(model_dt, "model_dt", "simulate", "s"),
                               allow_nonphysical)
    return Simulation(**run)


def compare(scene: SceneLike, mapping: str = "", geometry: str = "", model_dt: Optional[float] = None,
            integrator: Optional[str] = None, dt: Optional[float] = None,
            duration: Optional[float] = None, converged_tol: float = 1e-12,
            diagnosis: Union[bool, str] = True, allow_nonphysical: bool = False,
            engines: Sequence[str] = (), friction: str = "") -> dict:
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
    the diagnosis (``--no-diagnosis``)."""
    if isinstance(diagnosis, str) and diagnosis != "full":
        raise ValueError(f"compare(): diagnosis={diagnosis!r}: must be True, False or \"full\"")
    if not isinstance(diagnosis, (bool, str)):
        raise TypeError(f"compare(): diagnosis must be True, False or \"full\", "
                        f"not {type(diagnosis).__name__}")
    run = _contact2d._compare(_scene(scene, "compare"), integrator,
                              _number(dt, "dt", "compare", "s"),
                              _number(duration, "duration", "compare", "s"), mapping, geometry,
                              friction, _number(model_dt, "model_dt", "compare", "s"),
                              list(engines),
                              _number(converged_tol, "converged_tol", "compare", "m"),
                              diagnosis is not False, diagnosis == "full", allow_nonphysical)
    result = json.loads(run["json"])
    for key, value in run.items():
        if key != "json":
            result[key] = value
    return result


def generate(scene: SceneLike, mapping: str = "", geometry: str = "", model_dt: Optional[float] = None,
             integrator: Optional[str] = None, dt: Optional[float] = None,
             duration: Optional[float] = None, engine: str = "mujoco",
             friction: str = "") -> str:
    """The MuJoCo MJCF of the scene, as ``contact2d generate``: for MuJoCo
    2.2.2 (engine "mujoco") or MuJoCo 3 ("mujoco3", with friction "damper"
    if asked; not checked by MuJoCo 3 here, the engine loads it)."""
    run = _contact2d._generate(_scene(scene, "generate"), integrator,
                               _number(dt, "dt", "generate", "s"),
                               _number(duration, "duration", "generate", "s"), mapping, geometry,
                               friction, engine, _number(model_dt, "model_dt", "generate", "s"))
    _notes(run["notes"])
    return run["xml"]


def _required(value, name, function, unit):
    """A number that has no "absent": None is a TypeError naming the keyword."""
    if value is None:
        raise TypeError(f"{function}(): {name} must be a number ({unit}), not None")
    return value


def _path(value, name, function, optional=False):
    """A path given as str or os.PathLike, as str; "" stays "" when optional."""
    if isinstance(value, (str, os.PathLike)):
        path = os.fspath(value)
        if "\0" in path:  # the C library would stop the path there
            raise ValueError(f"{function}(): {name} has a NUL character, which no file "
                             "name can hold")
        return path
    raise TypeError(f"{function}(): {name} must be a path (str or os.PathLike"
                    f"{', or empty' if optional else ''}), not {type(value).__name__}")


def solref(k: Optional[float] = None, c: Optional[float] = None, *,
           dt: Optional[float] = None,
           mass: Optional[float] = None, mapping: str = "all", joint: Optional[str] = None,
           inertia: float = 0.0, lever: float = 0.0, pivot: float = 0.0,
           mu: Optional[float] = None, mu_roll: float = 0.0,
           model: Union[str, os.PathLike] = "", body: str = "",
           contacts: Optional[int] = None, restitution: Optional[float] = None,
           contact_time: Optional[float] = None,
           penetration: Optional[float] = None, engine: str = "mujoco", settle: float = 3.0,
           key: str = "", apply: Union[str, os.PathLike] = "",
           slope: Optional[float] = None) -> dict:
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
    ``apply`` (a path) writes that model with the recommendation. ``engine``
    is ``"mujoco"`` for 2.2.2 or ``"mujoco3"`` for 3.14."""
    def number(value, name, unit):
        return _number(value, name, "solref", unit)
    run = _contact2d._solref(number(k, "k", "N/m"), number(c, "c", "N·s/m"),
                             number(dt, "dt", "s"), number(mass, "mass", "kg"), mapping, joint,
                             number(inertia, "inertia", "kg·m²"), number(lever, "lever", "m"),
                             number(pivot, "pivot", "m"), number(mu, "mu", "dimensionless"),
                             number(mu_roll, "mu_roll", "m"),
                             _path(model, "model", "solref", True), body, contacts,
                             number(restitution, "restitution", "dimensionless"),
                             number(contact_time, "contact_time", "s"),
                             number(penetration, "penetration", "m"), engine,
                             _required(number(settle, "settle", "s"), "settle", "solref", "s"),
                             key,
                             _path(apply, "apply", "solref", True),
                             number(slope, "slope", "degrees"))
    _notes(run["notes"])
    return json.loads(run["json"])


def inspect(path: Union[str, os.PathLike], key: str = "", pairs: bool = False,
            slope: Optional[float] = None, settle: float = 0.0, estimate_loads: bool = False,
            engine: str = "mujoco", rest_search: bool = True) -> dict:
    """Any MJCF model's contacts in physical units, as
    ``contact2d inspect --json`` (docs/inspect.md): that JSON object as a
    dict. ``path``: the MJCF file (str or os.PathLike); ``key``: the
    keyframe to start from (default qpos0); ``settle``: seconds MuJoCo steps
    the model first, so it comes to rest on what it touches; ``slope``:
    degrees in [0, 90), each contact's creep speed under friction;
    ``pairs``: every geom pair's distance; ``estimate_loads``: loads from a
    body's weight where MuJoCo has none; ``engine``: ``"mujoco"`` for 2.2.2
    or ``"mujoco3"`` for 3.14; ``rest_search``: when the model is not at
    rest, settle it longer to say how long it takes (``--no-rest-search``
    is ``rest_search=False``)."""
    run = _contact2d._inspect(_path(path, "path", "inspect"), key, pairs,
                              _number(slope, "slope", "inspect", "degrees"),
                              _required(_number(settle, "settle", "inspect", "s"), "settle",
                                        "inspect", "s"), estimate_loads, engine,
                              bool(rest_search))
    _notes(run["notes"])
    return json.loads(run["json"])


@dataclass
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
    impacts: np.ndarray
    errors: np.ndarray
    predicted: np.ndarray
    measured: np.ndarray


@dataclass
class Fit:
    """What ``contact2d fit --json`` prints, as ``json`` (a dict), and its
    models with their per-impact arrays, as ``models`` (FitModel)."""
    json: dict
    models: List[FitModel]

    def model(self, name: str = "penalty", engine: str = "ref", split: str = "seeded") -> FitModel:
        """The one model of that name, engine and split."""
        for m in self.models:
            if (m.name, m.engine, m.split) == (name, engine, split):
                return m
        raise KeyError(f"fit: no model {name!r} on engine {engine!r}, split {split!r}")


def fit(recording: Union[str, os.PathLike], seed: int = 2026, bootstrap: int = 8,
        engines: Optional[Sequence[str]] = None, threads: int = 0, all_impacts: bool = False,
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
    if isinstance(seed, bool) or not isinstance(seed, numbers.Integral) or not 0 <= seed < 2**53:
        raise ValueError(f"fit(): seed = {seed!r}: an integer in [0, 2**53)")
    if isinstance(bootstrap, bool) or not isinstance(bootstrap, numbers.Integral) \
            or not 0 <= bootstrap <= 1000:
        raise ValueError(f"fit(): bootstrap = {bootstrap!r}: an integer in [0, 1000]")
    if isinstance(threads, bool) or not isinstance(threads, numbers.Integral) \
            or not 0 <= threads <= 256:
        raise ValueError(f"fit(): threads = {threads!r}: an integer in [0, 256] (0: one per core)")
    if engines is not None:
        if isinstance(engines, str):
            raise TypeError("fit(): engines must be a list of engine names, e.g. ['mujoco'], "
                            "not a string")
        engines = [str(e) for e in engines]
    run = _contact2d._fit(_path(recording, "recording", "fit"), int(seed), int(bootstrap),
                          engines, int(threads), bool(all_impacts), bool(k_profile))
    data = json.loads(run["json"])
    models = []
    for entry, arrays in zip(data["models"], run["arrays"]):
        models.append(FitModel(
            name=entry["name"], engine=entry["engine"], split=entry["split"],
            median=entry["median"], iqr=entry["iqr"], parameters=dict(entry["parameters"]),
            spread={k: tuple(v) for k, v in entry.get("spread_16_84", {}).items()},
            impacts=arrays["impacts"], errors=arrays["errors"], predicted=arrays["predicted"],
            measured=arrays["measured"]))
    return Fit(json=data, models=models)
