# Type stub of the compiled extension _contact2d (src/python/module.cpp),
# for editors, help and type checkers; shipped in the package with py.typed.
# tests/python/test_stubs.py checks that it names every public class,
# attribute and method of the extension, of the same kind (a read-only
# property is a @property here), and nothing else.
import os
from typing import Any, Dict, List, Optional, Sequence, Union

__version__: str
mujoco_available: bool

class BoxPart:
    """One rectangle of a tshape's body (body.parts)."""
    def __init__(self, width: float, height: float, x: float, y: float, mass: float) -> None: ...
    width: float  # m
    height: float  # m
    x: float  # centre x in the body frame, m
    y: float  # centre y in the body frame, m
    mass: float  # kg

class Contact:
    """[contact]: the contact law (docs/scenes.md)."""
    k: float  # stiffness, N/m
    c: float  # damping, N·s/m
    mu: float  # sliding friction coefficient
    alpha: float  # tanh regularisation of friction, s/m
    mu_roll: float  # rolling resistance, m
    mu_torsion: float  # torsional friction, m (MuJoCo only)
    cone_ratio: float  # the cone laws' ratio (MuJoCo's impratio)
    damping: str  # "compression" or "kelvin_voigt"
    friction_law: str  # "tanh", "viscous_cone" or "soft_cone"

class State:
    """[initial]: the initial state (docs/scenes.md)."""
    x: float  # m
    y: float  # m
    theta: float  # rad
    vx: float  # m/s
    vy: float  # m/s
    omega: float  # rad/s

class Sim:
    """[sim]: time stepping (docs/scenes.md)."""
    dt: float  # time step, s
    duration: float  # simulated time, s
    output_dt: float  # sample spacing of the trajectory, s
    gravity: float  # m/s²
    integrator: str  # "explicit_euler", "semi_implicit_euler", "implicit_euler" or "rk4"

class Scene:
    """A scene: body, contact, initial state, sim."""
    source: str  # the file Scene.load read (absent when built in Python)
    def __init__(self, shape: str = "point_mass") -> None: ...
    @staticmethod
    def load(path: Union[str, os.PathLike], set: Sequence[str] = ()) -> Scene: ...
    shape: str  # "point_mass", "box", "tshape", "circle" or "ellipse"
    mass: float  # kg
    half_height: float  # m
    width: float  # m
    height: float  # m
    radius: float  # m
    a: float  # m
    b: float  # m
    inertia: float  # kg·m²
    parts: List[BoxPart]
    contact: Contact
    initial: State
    sim: Sim
    @property
    def obstacles(self) -> int: ...
    def validate(self) -> None: ...
    def copy(self) -> Scene: ...

# The commands: contact2d's simulate, compare, ... call them.
def _simulate(scene: Scene, engine: str, integrator: Optional[str], dt: Optional[float],
              duration: Optional[float], mapping: str, geometry: str, friction: str,
              model_dt: Optional[float], allow_nonphysical: bool) -> Dict[str, Any]: ...
def _compare(scene: Scene, integrator: Optional[str], dt: Optional[float],
             duration: Optional[float], mapping: str, geometry: str, friction: str,
             model_dt: Optional[float], engines: List[str], converged_tol: float,
             diagnosis: bool, full_diagnosis: bool,
             allow_nonphysical: bool) -> Dict[str, Any]: ...
def _generate(scene: Scene, integrator: Optional[str], dt: Optional[float],
              duration: Optional[float], mapping: str, geometry: str, friction: str, engine: str,
              model_dt: Optional[float]) -> Dict[str, Any]: ...
def _inspect(path: str, key: str, pairs: bool, slope: Optional[float], settle: float,
             estimate_loads: bool, engine: str, rest_search: bool) -> Dict[str, Any]: ...
def _fit(path: str, seed: int, bootstrap: int, engines: Optional[List[str]], threads: int,
         all_impacts: bool, k_profile: bool) -> Dict[str, Any]: ...
def _solref(k: Optional[float], c: Optional[float], dt: Optional[float], mass: Optional[float],
            mapping: str, joint: Optional[str], inertia: float, lever: float, pivot: float,
            mu: Optional[float], mu_roll: float, model: str, body: str, contacts: Optional[int],
            restitution: Optional[float], contact_time: Optional[float],
            penetration: Optional[float], engine: str, settle: float, key: str, apply: str,
            slope: Optional[float]) -> Dict[str, Any]: ...
