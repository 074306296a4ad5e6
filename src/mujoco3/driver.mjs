// MuJoCo 3 (the WebAssembly package @mujoco/mujoco, pinned by
// package-lock.json) for contact2d's mujoco3 engine. The C++ side
// (mujoco3/node_process.cpp) starts one `node driver.mjs` per thread and
// talks to it over stdin/stdout:
//
//   request   one JSON line {"op": ..., ...}
//   answer    one JSON line {"ok": true, ...} or {"ok": false, "error": "one line"};
//             a "step" answer is followed by "bytes" bytes of little-endian
//             float64: per step taken, qpos (nq) then qvel (nv).
//
// ops: hello → {version, package}; load {xml} → {id, nq, nv, body_pos,
// body_invweight0, timestep}; free {id}; reset {id, qpos, qvel} (mj_resetData,
// then the given state); applied {id, body, xfrc};
// step {id, n} → {steps, bad, bytes}: up to n mj_step, stopping after the
// first one that left a bad number in qpos or qvel (MuJoCo's autoreset is
// off, so it stays there); rewind {id, n}: back to the state before the last
// "step" and n steps again (a changed applied force takes effect there);
// counters {id} → {warnings: ["text (N times)"]}.
//
// Everything MuJoCo prints (its warnings) is collected and returned as
// "messages" on the next answer, so stdout carries only the protocol.
import {readFileSync} from 'node:fs';
import {dirname, join} from 'node:path';
import {createInterface} from 'node:readline';
import {fileURLToPath} from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const messages = [];
const collect = (text) => messages.push(String(text));

let loadMujoco;
try {
  ({default: loadMujoco} = await import('@mujoco/mujoco'));
} catch (e) {
  process.stdout.write(JSON.stringify({
    ok: false,
    error: 'cannot import @mujoco/mujoco: ' + String(e && e.message ? e.message : e).split('\n')[0]
  }) + '\n');
  process.exit(3);
}
const packageVersion =
    JSON.parse(
            readFileSync(join(here, 'node_modules', '@mujoco', 'mujoco', 'package.json'), 'utf8'))
        .version;
const mj = await loadMujoco({print: collect, printErr: collect});

const models = new Map();  // id → {m, d, saved}
let nextId = 1;

function oneLine(e) {
  const text = String(e && e.message ? e.message : e);
  return text.replace(/\s+/g, ' ').trim();
}

function entry(request) {
  const e = models.get(request.id);
  if (!e) throw new Error(`no model ${request.id}`);
  return e;
}

function badCounters(d) {
  // mjWARN_BADQPOS, mjWARN_BADQVEL, mjWARN_BADQACC
  const w = d.warning;
  return w.get(mj.mjtWarning.mjWARN_BADQPOS.value).number +
      w.get(mj.mjtWarning.mjWARN_BADQVEL.value).number +
      w.get(mj.mjtWarning.mjWARN_BADQACC.value).number;
}

// The state a "rewind" returns to: everything mj_step reads that changes.
function save(e) {
  const d = e.d;
  e.saved = {
    time: d.time,
    qpos: d.qpos.slice(),
    qvel: d.qvel.slice(),
    act: d.act.slice(),
    warm: d.qacc_warmstart.slice()
  };
}

function restore(e) {
  const d = e.d, s = e.saved;
  d.time = s.time;
  d.qpos.set(s.qpos);
  d.qvel.set(s.qvel);
  d.act.set(s.act);
  d.qacc_warmstart.set(s.warm);
}

const ops = {
  hello: () =>
      ({version: mj.mj_versionString(), package: packageVersion, node: process.versions.node}),
  load: (r) => {
    const m = mj.MjModel.from_xml_string(r.xml);
    // Bad numbers stay in qpos/qvel, where "step" sees them at once, instead
    // of MuJoCo resetting mjData (its warning counters count them all the same).
    m.opt.disableflags |= mj.mjtDisableBit.mjDSBL_AUTORESET.value;
    const d = new mj.MjData(m);
    const id = nextId++;
    models.set(id, {m, d, saved: null});
    return {
      id,
      nq: m.nq,
      nv: m.nv,
      nbody: m.nbody,
      timestep: m.opt.timestep,
      body_pos: Array.from(m.body_pos),
      body_invweight0: Array.from(m.body_invweight0)
    };
  },
  free: (r) => {
    const e = entry(r);
    e.d.delete();
    e.m.delete();
    models.delete(r.id);
    return {};
  },
  reset: (r) => {
    const e = entry(r);
    mj.mj_resetData(e.m, e.d);
    e.d.qpos.set(r.qpos);
    e.d.qvel.set(r.qvel);
    e.saved = null;
    return {};
  },
  applied: (r) => {
    const e = entry(r);
    e.d.xfrc_applied.set(r.xfrc, 6 * r.body);
    return {};
  },
  step: (r) => {
    const e = entry(r);
    const { m, d } = e;
    const nq = m.nq, nv = m.nv, width = nq + nv;
    const out = new Float64Array(r.n * width);
    save(e);
    // Views into MuJoCo's memory, taken again if a step ever moved it.
    let qpos = d.qpos, qvel = d.qvel;
    let steps = 0, bad = false;
    while (steps < r.n) {
      mj.mj_step(m, d);
      if (qpos.length !== nq) ({ qpos, qvel } = d);
      const at = steps * width;
      out.set(qpos, at);
      out.set(qvel, at + nq);
      ++steps;
      // MuJoCo's own test (mju_isBad: NaN or beyond mjMAXVAL = 1e10), on
      // qpos and qvel; a bad qacc makes qvel bad in the same step. Reading
      // the warning counters instead costs more than the step.
      for (let i = at; i < at + width; ++i) {
        if (!(Math.abs(out[i]) <= 1e10)) bad = true;
      }
      if (bad) break;
    }
    const bytes = Buffer.from(out.buffer, 0, steps * width * 8);
    return { steps, bad, bytes: bytes.length, payload: bytes };
  },
  rewind: (r) => {
    const e = entry(r);
    if (!e.saved) throw new Error('rewind without a step');
    restore(e);
    for (let i = 0; i < r.n; ++i) mj.mj_step(e.m, e.d);
    return {};
  },
  counters: (r) => {
    const {d} = entry(r);
    const out = [];
    for (let i = 0; i < mj.mjtWarning.mjNWARNING.value; ++i) {
      const n = d.warning.get(i).number;
      if (n > 0) out.push(`${mj.mju_warningText(i, d.warning.get(i).lastinfo)} (${n} times)`);
    }
    return {warnings: out};
  },
};

const input = createInterface({input: process.stdin, crlfDelay: Infinity});
input.on('line', (line) => {
  let answer;
  try {
    const request = JSON.parse(line);
    const op = ops[request.op];
    if (!op) throw new Error(`unknown op ${request.op}`);
    answer = {ok: true, ...op(request)};
  } catch (e) {
    answer = {ok: false, error: oneLine(e)};
  }
  const payload = answer.payload;
  delete answer.payload;
  if (messages.length) answer.messages = messages.splice(0).map(oneLine);
  process.stdout.write(JSON.stringify(answer) + '\n');
  if (payload) process.stdout.write(payload);
});
input.on('close', () => process.exit(0));
