"""MuJoCo 3's Node process from Python (issue 49): Ctrl-C while MuJoCo 3
settles a model ends the call with KeyboardInterrupt at once (Node is
killed with the wait, src/io/child_process.hpp), a thread's Node that died
while idle is replaced on the next call, and a chatty Node (stderr) does
not hang a loop of calls. Every process killed here is one the test
started; every file is the test's own."""

import os
import signal
import subprocess
import sys
import time

import pytest

import contact2d
from conftest import needs



@pytest.fixture(autouse=True)
def needs_mujoco():
    needs(contact2d.mujoco_available, "needs MuJoCo")


def slow_model(folder):
    """A model MuJoCo takes minutes to settle for 1e300 s (1e6 steps)."""
    bodies = "".join(
        f'<body pos="{0.01 * (i % 5)} {0.01 * (i % 3)} {0.1 + 0.09 * i}"><freejoint/>'
        '<geom type="sphere" size=".04"/></body>' for i in range(40))
    path = folder / "slow.xml"
    path.write_text('<mujoco><option timestep="0.002"/><worldbody>'
                    f'<geom type="plane" size="1 1 .1"/>{bodies}</worldbody></mujoco>\n')
    return path


def node_children():
    """The pids of this process's Node children (driver.mjs)."""
    found = []
    for name in os.listdir("/proc"):
        if not name.isdigit():
            continue
        try:
            with open(f"/proc/{name}/stat", encoding="utf-8", errors="replace") as f:
                fields = f.read().rsplit(")", 1)[1].split()
            with open(f"/proc/{name}/cmdline", "rb") as f:
                cmdline = f.read()
        except OSError:
            continue
        if int(fields[1]) == os.getpid() and fields[0] != "Z" and b"driver.mjs" in cmdline:
            found.append(int(name))
    return found


SCRIPT = r"""
import os, signal, sys, threading, time
import contact2d
signal.signal(signal.SIGINT, signal.default_int_handler)  # ctest may start us with it ignored
path = sys.argv[1]
contact2d.inspect(path, settle=0.002, engine="mujoco3")  # Node started: time the settle only
sent = []
def ctrl_c():
    sent.append(time.monotonic())
    os.kill(os.getpid(), signal.SIGINT)
threading.Timer(1.5, ctrl_c).start()
try:
    contact2d.inspect(path, settle=1e300, engine="mujoco3")
    print("finished")
except KeyboardInterrupt:
    print("interrupted %.4f" % (time.monotonic() - sent[0]))
print(bool(contact2d.inspect(path, settle=0.01, engine="mujoco3")))
"""


def test_ctrl_c_while_mujoco3_settles(tmp_path):
    """Before: the call waited for the settle (1e6 steps, minutes)."""
    start = time.monotonic()
    done = subprocess.run([sys.executable, "-c", SCRIPT, str(slow_model(tmp_path))],
                          capture_output=True, text=True, env=os.environ, timeout=120,
                          check=False)
    wall = time.monotonic() - start
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert lines[0].startswith("interrupted "), done.stdout
    latency = float(lines[0].split()[1])
    print(f"mujoco3 settle: KeyboardInterrupt {latency:.4f} s after SIGINT; script {wall:.2f} s")
    assert latency < 30.0, done.stdout
    assert lines[1] == "True", done.stdout  # the next call works


def test_a_node_that_died_idle_does_not_fail_the_next_call(tmp_path):
    """Before: the next call failed once ("... was killed by signal 9")."""
    model = tmp_path / "ball.xml"
    model.write_text('<mujoco><worldbody><body><freejoint/><geom size=".1"/></body>'
                     "</worldbody></mujoco>\n")
    contact2d.inspect(str(model), engine="mujoco3")
    nodes = node_children()
    assert nodes
    for pid in nodes:
        os.kill(pid, signal.SIGKILL)
    for pid in nodes:  # until it can be reaped (every thread ended), without reaping it
        deadline = time.monotonic() + 5
        while time.monotonic() < deadline:
            info = os.waitid(os.P_PID, pid, os.WEXITED | os.WNOHANG | os.WNOWAIT)
            if info is not None and info.si_pid == pid:
                break
            time.sleep(0.01)
    report = contact2d.inspect(str(model), engine="mujoco3")
    assert report


LOOP = r"""
import sys
import contact2d
for i in range(8):
    contact2d.inspect(sys.argv[1], engine="mujoco3")
print("done")
"""


def test_a_chatty_node_does_not_hang_a_loop(tmp_path):
    """NODE_OPTIONS=--trace-sync-io: a stack trace on Node's stderr for each
    synchronous read. Before: the loop hung after the first call."""
    for i in range(20):
        (tmp_path / f"part{i}.xml").write_text('<mujoco><compiler angle="radian"/></mujoco>\n')
    includes = "".join(f'<include file="part{i}.xml"/>' for i in range(20))
    model = tmp_path / "model.xml"
    model.write_text(f"<mujoco>{includes}<worldbody><body><freejoint/><geom size=\".1\"/>"
                     "</body></worldbody></mujoco>\n")
    env = dict(os.environ, NODE_OPTIONS="--trace-sync-io")
    proc = subprocess.Popen([sys.executable, "-c", LOOP, str(model)], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, env=env)
    try:
        out, err = proc.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        proc.kill()
        out, err = proc.communicate()
        pytest.fail("a loop of inspect(engine='mujoco3') hung with a chatty Node")
    assert proc.returncode == 0, err
    assert out.strip() == "done"
