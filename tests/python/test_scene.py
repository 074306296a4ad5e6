"""Scene: every field of the scene file readable and settable from Python."""

import copy

import pytest

import contact2d

BOX = "validation/scenes/box.toml"


def test_load_reads_the_file():
    s = contact2d.Scene.load(BOX)
    assert s.source == BOX
    assert s.shape == "box"
    assert (s.mass, s.width, s.height) == (1.0, 0.4, 0.2)
    assert (s.contact.k, s.contact.c, s.contact.mu, s.contact.alpha) == (1e4, 50.0, 0.5, 100.0)
    assert s.contact.damping == "compression" and s.contact.friction_law == "tanh"
    assert (s.initial.x, s.initial.y, s.initial.theta, s.initial.vx) == (0.0, 0.6, 0.3, 1.0)
    assert (s.sim.dt, s.sim.duration, s.sim.integrator) == (1e-4, 2.0, "semi_implicit_euler")
    assert s.obstacles == 0
    assert repr(s).startswith("Scene(shape='box', mass=1.0, ")
    assert repr(s).endswith(f"obstacles=0, source={BOX!r})")


def test_fields_set_in_place():
    s = contact2d.Scene.load(BOX)
    s.contact.k = 2e4
    s.contact.damping = "kelvin_voigt"
    s.contact.friction_law = "soft_cone"
    s.initial.omega = 1.5
    s.sim.integrator = "rk4"
    s.sim.dt = 5e-4
    s.shape = "circle"
    s.radius = 0.2
    assert (s.contact.k, s.contact.damping, s.contact.friction_law) == (2e4, "kelvin_voigt",
                                                                          "soft_cone")
    assert (s.initial.omega, s.sim.integrator, s.sim.dt) == (1.5, "rk4", 5e-4)
    assert (s.shape, s.radius) == ("circle", 0.2)
    s.validate()


def test_set_fields_change_the_run():
    s = contact2d.Scene.load(BOX)
    base = contact2d.simulate(s, duration=1.0)
    s.contact.k = 5e4
    stiffer = contact2d.simulate(s, duration=1.0)
    assert base.trajectory.shape == stiffer.trajectory.shape
    assert (base.trajectory != stiffer.trajectory).any()
    # Keyword overrides leave the scene alone.
    contact2d.simulate(s, dt=2e-4, duration=0.1, integrator="rk4")
    assert (s.sim.dt, s.sim.duration, s.sim.integrator) == (1e-4, 2.0, "semi_implicit_euler")


def test_defaults_and_copies():
    s = contact2d.Scene("tshape")
    assert s.shape == "tshape" and not hasattr(s, "source")
    loaded = contact2d.Scene.load(BOX)
    for c in (loaded.copy(), copy.copy(loaded), copy.deepcopy(loaded)):
        assert c.source == BOX
        c.contact.k = 1.0
        assert loaded.contact.k == 1e4
    with pytest.raises(ValueError):
        contact2d.Scene("sphere")


def test_tshape_parts():
    s = contact2d.Scene("tshape")
    s.parts = [contact2d.BoxPart(0.6, 0.1, 0.0, 0.25, 0.6),
               contact2d.BoxPart(0.1, 0.4, 0.0, 0.0, 0.4)]
    assert [(p.width, p.mass) for p in s.parts] == [(0.6, 0.6), (0.1, 0.4)]
    run = contact2d.simulate(s, duration=0.05)
    assert run.column("t")[-1] == pytest.approx(0.05)
