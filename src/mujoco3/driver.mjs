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
// counters {id} → {warnings: ["text (N times)"]};
// state {path, key, settle} → a user's model file at one state, the fields
// of mujoco/model_state.hpp's ModelState (the model is loaded, settled,
// read and freed within the request).
//
// Everything MuJoCo prints (its warnings) is collected and returned as
// "messages" on the next answer, so stdout carries only the protocol.
import {lstatSync, readdirSync, readFileSync} from 'node:fs';
import {basename, dirname, join} from 'node:path';
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

// The package cannot read the disk: the model file is copied into MuJoCo's
// in-memory file system and, when MuJoCo cannot load it alone (an include,
// a mesh, a texture beside it), its whole folder, at most kStageBytes in
// all; removed after the request.
const kStageBytes = 256 * 1024 * 1024;
function stageFile(path) {
  const root = '/model';
  mj.FS.mkdirTree(root);
  mj.FS.writeFile(root + '/' + basename(path), readFileSync(path));
  return {root, file: root + '/' + basename(path)};
}

function stage(path) {
  const root = '/model';
  let bytes = 0;
  const copy = (from, to) => {
    mj.FS.mkdirTree(to);
    for (const entry of readdirSync(from, {withFileTypes: true})) {
      const source = join(from, entry.name), target = to + '/' + entry.name;
      if (entry.isDirectory()) {
        copy(source, target);
      } else if (entry.isFile()) {
        const data = readFileSync(source);
        bytes += data.length;
        if (bytes > kStageBytes) {
          throw new Error(`the model's folder ${dirname(path)} holds more than ` +
                          `${kStageBytes / 1048576} MiB (MuJoCo 3 reads a copy of it)`);
        }
        mj.FS.writeFile(target, data);
      }
    }
  };
  try {
    copy(dirname(path), root);
  } catch (e) {
    unstage(root);
    throw e;
  }
  return {root, file: root + '/' + basename(path)};
}

function unstage(path) {
  let info;
  try {
    info = mj.FS.stat(path);
  } catch {
    return;
  }
  if (mj.FS.isDir(info.mode)) {
    for (const name of mj.FS.readdir(path)) {
      if (name !== '.' && name !== '..') unstage(path + '/' + name);
    }
    mj.FS.rmdir(path);
  } else {
    mj.FS.unlink(path);
  }
}

// A name from the model's names buffer ("" when unnamed).
const decoder = new TextDecoder();
function nameAt(m, adr) {
  const names = m.names;
  let end = adr;
  while (names[end]) ++end;
  return decoder.decode(names.slice(adr, end));
}

const integrators = ['Euler', 'RK4', 'implicit', 'implicitfast'];

function readState(m, d, r) {
  const nv = m.nv, nbody = m.nbody, ngeom = m.ngeom;
  const obj = mj.mjtObj;
  let key = -1;
  if (r.key) {
    key = mj.mj_name2id(m, obj.mjOBJ_KEY.value, r.key);
    if (key < 0) {
      const names = [];
      for (let i = 0; i < m.nkey; ++i) names.push(nameAt(m, m.name_keyadr[i]) || `key #${i}`);
      throw new Error(`--key ${r.key}: no keyframe of that name in ${r.path}` +
                      (names.length ? ` (its keyframes: ${names.join(', ')})` : ' (it has none)'));
    }
    mj.mj_resetDataKeyframe(m, d, key);
  } else {
    mj.mj_resetData(m, d);
  }
  const where = `${r.option ? r.option + ' ' : ''}${r.path}: `;
  if (!(m.opt.timestep > 0) || !Number.isFinite(m.opt.timestep)) {
    throw new Error(`${where}<option timestep> is ${m.opt.timestep} s: MuJoCo steps only with a ` +
                    'finite timestep > 0');
  }
  for (let i = 0; i < m.nq; ++i) {
    if (!Number.isFinite(d.qpos[i])) {
      throw new Error((key >= 0 ? `--key ${r.key}: its qpos` : `${where}qpos0`) +
                      ` has a number that is not finite (${d.qpos[i]} at qpos[${i}])`);
    }
  }
  const steps = Math.min(1000000, Math.round(r.settle / m.opt.timestep));
  for (let i = 0; i < steps; ++i) mj.mj_step(m, d);
  mj.mj_forward(m, d);
  if (badCounters(d) > 0) {
    // Marked so the C++ side makes it an engine failure (exit 3), not bad input.
    throw new Error(`diverged: ${where}MuJoCo diverged while settling: there is no settled ` +
                    'state to read');
  }
  let speed = 0, accel = 0;
  for (let i = 0; i < nv; ++i) {
    speed = Math.max(speed, Math.abs(d.qvel[i]));
    accel = Math.max(accel, Math.abs(d.qacc[i]));
  }
  const warnings = [];
  for (let i = 0; i < mj.mjtWarning.mjNWARNING.value; ++i) {
    const n = d.warning.get(i).number;
    if (n > 0) warnings.push(`${mj.mju_warningText(i, d.warning.get(i).lastinfo)} (${n} times)`);
  }
  const disable = m.opt.disableflags, bits = mj.mjtDisableBit;
  const out = {
    version: mj.mj_versionString(),
    timestep: m.opt.timestep,
    integrator: integrators[m.opt.integrator] ?? `integrator ${m.opt.integrator}`,
    elliptic: m.opt.cone === mj.mjtCone.mjCONE_ELLIPTIC.value,
    impratio: m.opt.impratio,
    gravity: Array.from(m.opt.gravity),
    refsafe: !(disable & bits.mjDSBL_REFSAFE.value),
    disabled: disable & bits.mjDSBL_CONTACT.value      ? 'contacts'
        : disable & bits.mjDSBL_CONSTRAINT.value ? 'constraints'
                                                 : '',
    body_names: [],
    geom_names: [],
    body_weld: Array.from(m.body_weldid),
    body_mass: Array.from(m.body_mass),
    body_inertia: Array.from(m.body_inertia),
    body_invweight0: Array.from(m.body_invweight0),
    geom_body: Array.from(m.geom_bodyid),
    body_parent: Array.from(m.body_parentid),
    body_joints: Array.from({length: nbody}, () => []),
    geom_mu: Array.from({length: ngeom}, (_, g) => m.geom_friction[3 * g]),
    geom_condim: Array.from(m.geom_condim),
    geom_collides: Array.from({length: ngeom}, (_, g) => (m.geom_contype[g] | m.geom_conaffinity[g]) !== 0),
    nv,
    settled: steps * m.opt.timestep,
    speed,
    accel,
    step_warnings: warnings,
    contacts: []
  };
  const jointTypes = ['free', 'ball', 'slide', 'hinge'];
  for (let j = 0; j < m.njnt; ++j) out.body_joints[m.jnt_bodyid[j]].push(jointTypes[m.jnt_type[j]]);
  out.body_joints = out.body_joints.map((list) => list.join(', '));
  for (let b = 0; b < nbody; ++b)
    out.body_names.push(nameAt(m, m.name_bodyadr[b]) || (b === 0 ? 'world' : `body #${b}`));
  for (let g = 0; g < ngeom; ++g) out.geom_names.push(nameAt(m, m.name_geomadr[g]) || `geom #${g}`);

  out.qvel = Array.from(d.qvel);
  out.qacc = Array.from(d.qacc);

  const jp1 = new mj.DoubleBuffer(3 * nv), jp2 = new mj.DoubleBuffer(3 * nv);
  const jr = new mj.DoubleBuffer(3 * nv), x = new mj.DoubleBuffer(nv);
  const force = new mj.DoubleBuffer(6);
  try {
    for (let i = 0; i < d.ncon; ++i) {
      const con = d.contact.get(i);
      if (con.exclude !== 0 || con.efc_address < 0) continue;  // not in the constraint problem
      const g1 = con.geom1, g2 = con.geom2;
      const b1 = m.geom_bodyid[g1], b2 = m.geom_bodyid[g2];
      const pos = Array.from(con.pos), normal = Array.from(con.frame).slice(0, 3);
      mj.mj_jac(m, d, jp1, jr, pos, b1);
      mj.mj_jac(m, d, jp2, jr, pos, b2);
      const j1 = Float64Array.from(jp1.GetView()), j2 = Float64Array.from(jp2.GetView());
      const row = new Array(nv).fill(0);
      for (let k = 0; k < 3; ++k)
        for (let c = 0; c < nv; ++c) row[c] += normal[k] * (j2[k * nv + c] - j1[k * nv + c]);
      // A along a direction of the contact frame: n·J·M⁻¹·Jᵀ·n.
      const along = (axis) => {
        const out = new Array(nv).fill(0);
        for (let k = 0; k < 3; ++k)
          for (let c = 0; c < nv; ++c) out[c] += axis[k] * (j2[k * nv + c] - j1[k * nv + c]);
        return out;
      };
      mj.mj_solveM(m, d, x, row);
      const solved = Float64Array.from(x.GetView());
      let A = 0;
      for (let c = 0; c < nv; ++c) A += row[c] * solved[c];
      let A_t = 0;
      const tangents = [];
      if (con.dim >= 3) {
        const frame = Array.from(con.frame);
        for (const axis of [frame.slice(3, 6), frame.slice(6, 9)]) {
          const t = along(axis);
          mj.mj_solveM(m, d, x, t);
          const tx = Float64Array.from(x.GetView());
          let a = 0;
          for (let c = 0; c < nv; ++c) a += t[c] * tx[c];
          A_t = Math.max(A_t, a);
          tangents.push({row: t, solved: Array.from(tx)});
        }
      }
      const sparse = (dense) => ({
        index: dense.flatMap((v, c) => v !== 0 ? [c] : []),
        value: dense.filter((v) => v !== 0)
      });
      mj.mj_contactForce(m, d, i, force);
      const elliptic = m.opt.cone === mj.mjtCone.mjCONE_ELLIPTIC.value;
      const rows = elliptic || con.dim === 1 ? con.dim : 2 * (con.dim - 1);
      // From the forces, as mujoco/model_state.cpp's quadratic_rows (efc_state
      // is stale after the solver's early exits).
      const f = d.efc_force.slice(con.efc_address, con.efc_address + rows);
      let quadratic = 0;
      if (elliptic && con.dim > 1) {
        let t = 0;
        for (let k = 1; k < rows; ++k) t += (f[k] / con.friction[k - 1]) ** 2;
        quadratic = f[0] > 0 && Math.sqrt(t) < f[0] * (1 - 1e-9) ? rows : 0;
      } else {
        for (let k = 0; k < rows; ++k) quadratic += f[k] > 0;
      }
      // MuJoCo 3's collision driver: a pair's own margin and gap, else the two geoms' summed.
      let explicitPair = false;
      let margin = m.geom_margin[g1] + m.geom_margin[g2], gap = m.geom_gap[g1] + m.geom_gap[g2];
      for (let p = 0; p < m.npair; ++p) {
        const p1 = m.pair_geom1[p], p2 = m.pair_geom2[p];
        if ((p1 === g1 && p2 === g2) || (p1 === g2 && p2 === g1)) {
          explicitPair = true;
          margin = m.pair_margin[p];
          gap = m.pair_gap[p];
        }
      }
      out.contacts.push({
        geom1: g1,
        geom2: g2,
        body1: b1,
        body2: b2,
        explicit_pair: explicitPair,
        dist: con.dist - con.includemargin,
        pos,
        normal,
        condim: con.dim,
        friction: Array.from(con.friction),
        solref: Array.from(con.solref),
        solimp: Array.from(con.solimp),
        margin,
        gap,
        A,
        A_t,
        tangents: tangents.map((t) => ({row: sparse(t.row), solved: sparse(t.solved)})),
        force: force.GetView()[0],
        rows,
        quadratic,
        jacobian_index: row.flatMap((v, c) => v !== 0 ? [c] : []),
        jacobian_value: row.filter((v) => v !== 0),
        solved_index: Array.from(solved).flatMap((v, c) => v !== 0 ? [c] : []),
        solved_value: Array.from(solved).filter((v) => v !== 0)
      });
    }
  } finally {
    for (const b of [jp1, jp2, jr, x, force]) b.delete();
  }
  // The gravity load at this configuration, at rest: qfrc_bias at qvel = 0,
  // in the same mjData (as mujoco/model_state.cpp does).
  d.qvel.fill(0);
  mj.mj_forward(m, d);
  out.bias = Array.from(d.qfrc_bias);
  return out;
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
  state: (r) => {
    let {root, file} = stageFile(r.path);
    try {
      const before = messages.length;
      let m;
      try {
        m = mj.MjModel.from_xml_path(file);
      } catch {
        // Alone it does not load: with its folder (includes, meshes), or
        // MuJoCo's message about the model itself.
        messages.splice(before);
        unstage(root);
        ({root, file} = stage(r.path));
        try {
          m = mj.MjModel.from_xml_path(file);
        } catch (e) {
          throw new Error(`${r.option ? r.option + ' ' : ''}${r.path}: MuJoCo ` +
                          `${mj.mj_versionString()} cannot load the model: ${oneLine(e)}`);
        }
      }
      const loadWarning = messages.splice(before).map(oneLine).join('; ');
      const d = new mj.MjData(m);
      try {
        return {...readState(m, d, r), load_warning: loadWarning};
      } finally {
        d.delete();
        m.delete();
      }
    } finally {
      unstage(root);
    }
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
