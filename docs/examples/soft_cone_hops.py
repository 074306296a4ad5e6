"""How often one corner of docs/examples/soft_cone_slide.toml touches the
ground in 0.405-0.43 s, and how high it hops, at three steps; and whether the
two engines ever disagree on a corner's contact (docs/physics.md).

    PYTHONPATH=build/python /usr/bin/python3 docs/examples/soft_cone_hops.py
"""
import pathlib

import numpy as np

import contact2d

scene = contact2d.Scene.load(pathlib.Path(__file__).with_name("soft_cone_slide.toml"))
scene.sim.duration = 0.43
for dt in (1e-4, 1e-5, 1e-6):
    scene.sim.dt = dt
    scene.sim.output_dt = dt
    run = contact2d.simulate(scene)
    t, y, theta = run.column("t"), run.column("y"), run.column("theta")
    # The corner at (−w/2, −h/2) in the body frame.
    height = y + np.sin(theta) * -0.2 - np.cos(theta) * 0.1
    window = (t > 0.405) & (t < 0.43)
    touching = height[window] < 0.0
    switches = int(np.count_nonzero(touching[1:] != touching[:-1]))
    print(f"dt = {dt:g} s: {switches} contact switches, hops up to {height[window].max():.3g} m")

# Both engines at Δt = 1e-4 s over the whole run: steps at which a lower
# corner touches in one and not in the other.
scene.sim.dt = scene.sim.output_dt = 1e-4
scene.sim.duration = 1.5
touching = []
for engine in ("ref", "mujoco:compensated"):
    run = contact2d.simulate(scene, engine=engine)
    y, theta = run.column("y"), run.column("theta")
    touching.append([y + np.sin(theta) * x - np.cos(theta) * 0.1 < 0.0 for x in (-0.2, 0.2)])
differ = int(np.count_nonzero(np.any(np.array(touching[0]) != np.array(touching[1]), axis=0)))
print(f"ref and mujoco:compensated at dt = 1e-4 s: {differ} steps with a corner touching in one only")
