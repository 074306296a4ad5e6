"""Ctrl-C while the module's code runs (src/python/interruptible.hpp).

Each case starts a fresh interpreter that runs a call of many seconds and
sends itself SIGINT 1 s in: the call must end with KeyboardInterrupt, long
before it would have finished, and the interpreter goes on (the script
prints after catching it, then runs a short call, which must work: the
request to stop does not outlive the interrupt). The time from the signal
to the exception is printed; the module polls Python's signals every 20 ms
and the work looks every 1024 steps, so it is tens of milliseconds (the
aim: under 0.5 s; measured 12-19 ms on an idle machine). It is printed,
not asserted: a wall-clock bound fails on a loaded machine, not on the code
(1.25 s for mujoco3 with two builds running on 2 cores). What is asserted
is the behaviour: the call ends with KeyboardInterrupt within 30 s of the
signal, where finishing would take 1e9 steps (minutes on any engine)."""

import os
import subprocess
import sys
import time

import pytest

import contact2d
from conftest import needs

SCRIPT = r"""
import os, signal, sys, threading, time
import contact2d
signal.signal(signal.SIGINT, signal.default_int_handler)  # ctest may start us with it ignored
scene = contact2d.Scene.load("validation/scenes/box.toml")
scene.sim.output_dt = 1.0  # the long runs below keep 1e4 samples (at most 1e7 are kept)
sent = []
def ctrl_c():
    sent.append(time.monotonic())
    os.kill(os.getpid(), signal.SIGINT)
threading.Timer(1.0, ctrl_c).start()
call = sys.argv[1]
try:
    if call == "simulate":
        contact2d.simulate(scene, engine=sys.argv[2], dt=1e-5, duration=1e4)
    elif call == "compare":
        contact2d.compare(scene, dt=1e-5, duration=1e4)
    print("finished")
except KeyboardInterrupt:
    print("interrupted %.4f" % (time.monotonic() - sent[0]))
print(contact2d.simulate(scene, dt=1e-3, duration=0.1).summary)
"""


def engines():
    names = ["ref"]
    if contact2d.mujoco_available:
        names += ["mujoco", "mujoco3"]
    return names


@pytest.mark.parametrize("call", [("simulate", e) for e in engines()] + [("compare", "")])
def test_ctrl_c_stops_the_call_with_keyboard_interrupt(call):
    needs(call[0] != "compare" or contact2d.mujoco_available, "compare needs MuJoCo")
    # A run of 1e4 s at dt = 1e-5 is 1e9 steps: minutes on any engine.
    start = time.monotonic()
    done = subprocess.run([sys.executable, "-c", SCRIPT, *call], capture_output=True, text=True,
                          env=os.environ, timeout=120, check=False)
    wall = time.monotonic() - start
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert lines[0].startswith("interrupted "), done.stdout
    latency = float(lines[0].split()[1])
    print(f"{call}: KeyboardInterrupt {latency:.4f} s after SIGINT; whole script {wall:.2f} s")
    assert latency < 30.0, done.stdout
    assert lines[1].startswith("box [ref, semi_implicit_euler, dt = 0.001 s"), done.stdout


OTHER_THREAD_SCRIPT = r"""
import os, signal, threading, time
import contact2d
signal.signal(signal.SIGINT, signal.default_int_handler)
scene = contact2d.Scene.load("validation/scenes/box.toml")
scene.sim.output_dt = 1.0  # the long runs below keep 1e4 samples (at most 1e7 are kept)
caught = []
def other():
    try:
        contact2d.simulate(scene, dt=1e-5, duration=1e4)
        caught.append("finished")
    except contact2d.Cancelled as e:
        caught.append("Cancelled " + str(e))
    except Exception as e:
        caught.append(type(e).__name__ + " " + str(e))
worker = threading.Thread(target=other)
worker.start()
time.sleep(0.5)
threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
try:
    contact2d.simulate(scene, dt=1e-5, duration=1e4)
    print("main finished")
except KeyboardInterrupt:
    print("main interrupted")
worker.join(60)
print(caught[0] if caught else "worker still running")
"""


def test_ctrl_c_ends_other_threads_calls_with_cancelled():
    # Before: the other thread's call raised an undocumented
    # "RuntimeError: cancelled" (issue 50); it is contact2d.Cancelled, a
    # RuntimeError, with a message that says why.
    done = subprocess.run([sys.executable, "-c", OTHER_THREAD_SCRIPT], capture_output=True,
                          text=True, env=os.environ, timeout=120, check=False)
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert lines[0] == "main interrupted", done.stdout
    assert lines[1].startswith("Cancelled cancelled: Ctrl-C on the main thread"), done.stdout
    assert issubclass(contact2d.Cancelled, RuntimeError)
