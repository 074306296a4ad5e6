// MuJoCo 3 (the WebAssembly package @mujoco/mujoco, pinned by
// package-lock.json) for contact2d's mujoco3 engine. The C++ side
// (mujoco3/node_mujoco.cpp) starts one `node driver.mjs` per thread and
// talks to it over stdin/stdout:
//
//   request   one JSON line {"op": ..., ...}
//   answer    one JSON line {"ok": true, ...} or {"ok": false, "error": "one line"};
//             a "step" answer is followed by "bytes" bytes of little-endian
//             float64: per step taken, qpos (nq) then qvel (nv).
//
// ops: hello {protocol} → {version, package, node, protocol} (the
// protocol is PROTOCOL on both sides: a driver of another checkout, reached
// through $CONTACT2D_MUJOCO3_DIR, refuses to speak; so does the C++ side);
// load {xml} → {id, nq, nv, body_pos, body_invweight0, timestep}; free {id};
// reset {id, qpos, qvel} (mj_resetData, then the given state); applied {id,
// body, xfrc};
// step {id, n} → {steps, bad, bytes}: up to n mj_step, stopping after the
// first one that raised MuJoCo's bad-number counters (qpos, qvel, qacc: the
// test of 2.2.2's MujocoStepper; MuJoCo's autoreset is off, so the state
// stays there); bytes is exactly steps·(nq+nv)·8; rewind {id, n}:
// back to the state before the last "step" and n steps again (a changed
// applied force takes effect there);
// counters {id} → {warnings: ["text (N times)"]};
// a user's model file at one state, in requests of bounded work so that the
// C++ side can give each a deadline and cancel between them:
//   open {path, key, settle, option} → {handle, steps}: staged, compiled,
//     reset (to the keyframe) and checked; steps = the settling steps asked;
//   settle {handle, n, ms} → {done}: up to n mj_step, fewer when ms ms of
//     wall time have passed (done ≥ 1 when n ≥ 1);
//   read {handle} → <option> decoded and MuJoCo's own arrays at the state
//     (the fields of mujoco/state_arrays.hpp's StateArrays: each contact as
//     mjContact has it, with mj_jac of both bodies and mj_contactForce);
//   solve {handle, rows: [{index, value}]} → {rows}: mj_solveM of each
//     sparse row at that state;
//   close {handle}: the model freed.
//
// An answer {"ok": false, "error": ..., "fatal": true} means MuJoCo's
// WebAssembly aborted (its memory is then unusable): the driver exits after
// it. Every error carries what MuJoCo printed during the request ("Cannot
// enlarge memory ..."), which is otherwise returned as "messages" on the
// next answer, so stdout carries only the protocol.
import {closeSync, fstatSync, openSync, readdirSync, readFileSync, readSync, statSync} from 'node:fs';
import {dirname, isAbsolute, join, resolve} from 'node:path';
import {createInterface} from 'node:readline';
import {fileURLToPath} from 'node:url';

// The version of this protocol; node_mujoco.hpp's kProtocol.
const PROTOCOL = 6;

const here = dirname(fileURLToPath(import.meta.url));
const messages = [];
const collect = (text) => messages.push(String(text));

// Node ends with its parent: its input closing ends it (below), and so does
// the parent's death seen here (every request is bounded work, so the event
// loop runs at least every second or so). The C++ side also has the kernel
// send SIGKILL at its death (PR_SET_PDEATHSIG), which reaches a busy Node.
const parent = process.ppid;
setInterval(() => {
  if (process.ppid !== parent) process.exit(0);
}, 500).unref();

let mj, packageVersion;
try {
  const {default: loadMujoco} = await import('@mujoco/mujoco');
  packageVersion =
      JSON.parse(readFileSync(join(here, 'node_modules', '@mujoco', 'mujoco', 'package.json'),
                              'utf8'))
          .version;
  mj = await loadMujoco({print: collect, printErr: collect});
} catch (e) {
  // Answered to the first request (hello); the C++ side makes it an input
  // error (exit 2) naming the command that reinstalls the package.
  // Emscripten's note on file URIs is noise here; anything else it printed
  // is said after the error.
  const first = String(e && e.message ? e.message : e).split('\n')[0];
  const inner = first.replace(/^Aborted\((.*)\)$/, '$1');
  const said = messages.map(oneLine).filter(
      (t) => t && !/^warning: Loading from a file URI/.test(t) && !first.includes(t) &&
          !t.includes(inner));
  process.stdout.write(JSON.stringify({
    ok: false,
    error: 'cannot import @mujoco/mujoco: ' + first +
        (said.length ? ` (MuJoCo: ${said.join('; ')})` : '')
  }) + '\n', () => process.exit(3));
  await new Promise(() => {});
}

const models = new Map();  // id → {m, d, saved}
let nextId = 1;

function oneLine(e) {
  const text = String(e && e.message ? e.message : e);
  return text.replace(/\s+/g, ' ').trim();
}

function entry(id) {
  const e = models.get(id);
  if (!e) throw new Error(`no model ${id}`);
  return e;
}

// A model and its data freed (and its staged files, for a user's model).
function close(id) {
  const e = entry(id);
  models.delete(id);
  e.d.delete();
  e.m.delete();
  if (e.stage) e.stage.remove();
}

function badCounters(d) {
  // mjWARN_BADQPOS, mjWARN_BADQVEL, mjWARN_BADQACC
  const w = d.warning;
  return w.get(mj.mjtWarning.mjWARN_BADQPOS.value).number +
      w.get(mj.mjtWarning.mjWARN_BADQVEL.value).number +
      w.get(mj.mjtWarning.mjWARN_BADQACC.value).number;
}

// The state a "rewind" returns to: everything mj_step reads that changes,
// and MuJoCo's warning counters, so that after a rewind they count the
// steps taken since, not those of the batch run ahead and not read.
function save(e) {
  const d = e.d;
  const warnings = [];
  for (let i = 0; i < mj.mjtWarning.mjNWARNING.value; ++i) {
    const w = d.warning.get(i);
    warnings.push([w.number, w.lastinfo]);
    w.delete();
  }
  e.saved = {
    time: d.time,
    qpos: d.qpos.slice(),
    qvel: d.qvel.slice(),
    act: d.act.slice(),
    warm: d.qacc_warmstart.slice(),
    warnings
  };
}

function restore(e) {
  const d = e.d, s = e.saved;
  d.time = s.time;
  d.qpos.set(s.qpos);
  d.qvel.set(s.qvel);
  d.act.set(s.act);
  d.qacc_warmstart.set(s.warm);
  s.warnings.forEach(([number, lastinfo], i) => {
    const w = d.warning.get(i);
    w.number = number;
    w.lastinfo = lastinfo;
    d.warning.set(i, w);
    w.delete();
  });
}

// Up to n mj_step into out (qpos, qvel per step); the count taken. A step
// is bad as on 2.2.2 (mujoco/stepper.cpp): it raised MuJoCo's bad-number
// counters (mj_checkPos and mj_checkVel on the state it started from,
// mj_checkAcc on qacc; mju_isBad: NaN or beyond mjMAXVAL = 1e10). Reading
// the counters costs more than the step, so they are read only after a step
// that left a bad number in qpos, qvel or qacc, and once at the end (the
// caller). e.found: this call stopped at a bad step.
function runSteps(e, out, n, before) {
  const {m, d} = e;
  const nq = m.nq, width = nq + m.nv;
  // Views into MuJoCo's memory, taken again if a step ever moved it.
  let qpos = d.qpos, qvel = d.qvel, qacc = d.qacc;
  e.found = false;
  // A counter already raised: every step is bad, as on 2.2.2.
  if (before > 0) n = 1;
  let steps = 0;
  while (steps < n) {
    mj.mj_step(m, d);
    if (qpos.length !== nq) ({qpos, qvel, qacc} = d);
    const at = steps * width;
    out.set(qpos, at);
    out.set(qvel, at + nq);
    ++steps;
    let suspect = before > 0;
    for (let i = at; i < at + width; ++i) {
      if (!(Math.abs(out[i]) <= 1e10)) suspect = true;
    }
    for (let i = 0; i < qacc.length; ++i) {
      if (!(Math.abs(qacc[i]) <= 1e10)) suspect = true;
    }
    if (suspect && badCounters(d) > before) {
      e.found = true;
      break;
    }
  }
  return steps;
}

// The package cannot read the disk: the model is copied into MuJoCo's
// in-memory file system at its own absolute path, so that every name in it
// resolves there as on the disk (../, absolute paths). First the file
// alone; when MuJoCo cannot load it so, its folder (an include, a mesh, a
// texture beside it), then, one at a time, each file MuJoCo still names
// and cannot open (outside the folder, under a symlink). Sizes are checked
// before anything is read: at most kStageBytes in all; the file's kind too
// (a device or a FIFO would be read without end). Removed after the
// request.
const kStageBytes = 256 * 1024 * 1024;
const kStageFiles = 10000;
const utf8 = new TextDecoder('utf-8', {fatal: true});

class Stage {
  constructor(model) {
    this.model = resolve(model);
    this.files = [];  // staged, in order
    this.dirs = [];   // created, in order
    this.bytes = 0;
  }
  mkdirs(dir) {
    const missing = [];
    for (let d = dir; d !== '/' && !this.exists(d); d = dirname(d)) missing.unshift(d);
    for (const d of missing) {
      mj.FS.mkdir(d);
      this.dirs.push(d);
    }
  }
  exists(path) {
    try {
      mj.FS.stat(path);
      return true;
    } catch {
      return false;
    }
  }
  // One file of the disk at its path (or at `as`); false when it is staged
  // already. `why` names where the name came from, for the one line of a
  // refusal.
  file(path, why, as = path) {
    if (this.exists(as)) return false;
    let info;
    try {
      info = statSync(path);  // follows a symlink, as MuJoCo 2.2.2 does
    } catch (e) {
      const said = e.code === 'ENOENT' ? 'no such file' : e.code || oneLine(e);
      throw new Error(`${path}${why}: cannot read it (${said})`);
    }
    if (!info.isFile()) {
      throw new Error(`${path}${why}: not a regular file (MuJoCo 3 reads a copy of what the ` +
                      'model names, and this would not end)');
    }
    this.add(info.size, path);
    const fd = openSync(path, 'r');
    let data;
    try {
      // Exactly the size stat said: a file that grows is not read on.
      data = Buffer.alloc(info.size);
      let at = 0;
      while (at < data.length) {
        const n = readSync(fd, data, at, data.length - at, at);
        if (n <= 0) break;
        at += n;
      }
      if (fstatSync(fd).size !== info.size) throw new Error(`${path}${why}: changed while read`);
    } finally {
      closeSync(fd);
    }
    this.mkdirs(dirname(as));
    mj.FS.writeFile(as, data);
    this.files.push(as);
    return true;
  }
  add(size, path) {
    this.bytes += size;
    if (this.bytes > kStageBytes) {
      throw new Error(`${path}: the model's files come to more than ${kStageBytes / 1048576} ` +
                      'MiB (MuJoCo 3 reads a copy of them in memory)');
    }
  }
  // The model's folder, each file's size known before it is read: what
  // would not fit in kStageBytes, or past kStageFiles files, is left for
  // MuJoCo to ask for (below), so an unrelated big sibling changes nothing.
  // Names that are not UTF-8 cannot be named by a model, which is UTF-8
  // text: they are left out. A symlinked folder is followed on demand only.
  folder() {
    let files = 0;
    const read = (from) => {
      for (const entry of readdirSync(Buffer.from(from), {withFileTypes: true, encoding: 'buffer'})) {
        let name;
        try {
          name = utf8.decode(entry.name);
        } catch {
          continue;
        }
        const source = join(from, name);
        let info;
        try {
          info = statSync(source);
        } catch {
          continue;  // a dangling symlink: MuJoCo says so if the model names it
        }
        if (info.isDirectory()) {
          if (entry.isDirectory()) read(source);
        } else if (info.isFile() && this.bytes + info.size <= kStageBytes &&
                   ++files <= kStageFiles) {
          try {
            this.file(source, '');
          } catch {
            continue;  // unreadable: MuJoCo asks for it below if the model names it
          }
          // MuJoCo 3 reads a '\\' in a model's file names as '/' (2.2.2 as
          // a character of the name): the file is staged under both.
          if (name.includes('\\') && this.bytes + info.size <= kStageBytes) {
            try {
              this.file(source, '', join(from, name.replaceAll('\\', '/')));
            } catch {
              // a folder of that name exists: the model cannot mean both
            }
          }
        }
      }
    };
    read(dirname(this.model));
  }
  remove() {
    for (const f of this.files.reverse()) mj.FS.unlink(f);
    for (const d of this.dirs.reverse()) mj.FS.rmdir(d);
    this.files = [];
    this.dirs = [];
  }
}

// The name of the file MuJoCo could not open, resolved as 2.2.2 resolves it
// (an include's file relative to the model's folder; an asset's path comes
// whole), or null.
function missingFile(error, model) {
  const found = /Error opening file '([^']*)'/.exec(error) ||
      /could not open file '([^']*)'/i.exec(error) || /resource not found[^']*'([^']*)'/.exec(error);
  if (!found) return null;
  return isAbsolute(found[1]) ? found[1] : resolve(dirname(model), found[1]);
}

// MuJoCo 3 compiling the model at `path` from its staged copy.
function compile(path, where) {
  const stage = new Stage(path);
  const before = messages.length;
  try {
    stage.file(stage.model, '');
    const attempt = () => {
      try {
        return {m: mj.MjModel.from_xml_path(stage.model)};
      } catch (e) {
        // What MuJoCo printed on the way is part of its refusal ("Cannot
        // enlarge memory ..." before a bad_alloc).
        const said = messages.splice(before).map(oneLine).filter((t) => t);
        return {error: oneLine(e) + (said.length ? ` (MuJoCo: ${said.join('; ')})` : '')};
      }
    };
    let tried = attempt();
    if (tried.error) {
      stage.folder();
      tried = attempt();
    }
    for (let more = 0; tried.error && more < 10000; ++more) {
      const file = missingFile(tried.error, stage.model);
      if (!file || !stage.file(file, ` (named by ${where}${path})`)) break;
      tried = attempt();
    }
    if (tried.error) {
      throw new Error(`${where}${path}: MuJoCo ${mj.mj_versionString()} cannot load the model: ` +
                      tried.error);
    }
    return {m: tried.m, stage, loadWarning: messages.splice(before).map(oneLine).join('; ')};
  } catch (e) {
    stage.remove();
    throw e;
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

// The model reset to its keyframe (or qpos0) and checked; the steps of the
// settling asked for.
function prepareState(m, d, r) {
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
  return Math.min(1000000, Math.round(r.settle / m.opt.timestep));
}

// A sparse row: its non-zero columns and their values.
const sparse = (dense) => {
  const index = [], value = [];
  for (let c = 0; c < dense.length; ++c) {
    if (dense[c] !== 0) {
      index.push(c);
      value.push(dense[c]);
    }
  }
  return {index, value};
};

// The settled state (`steps` taken by "settle") as MuJoCo's own arrays:
// contact2d reads them (mujoco/state_arrays.cpp, the reader 2.2.2's arrays
// go through too). What only MuJoCo can compute comes along: each
// contact's mj_jac of both bodies and mj_contactForce; mj_solveM is "solve".
function readState(m, d, r, steps) {
  const nv = m.nv, nbody = m.nbody, ngeom = m.ngeom;
  const where = `${r.option ? r.option + ' ' : ''}${r.path}: `;
  mj.mj_forward(m, d);
  if (badCounters(d) > 0) {
    // Marked so the C++ side makes it an engine failure (exit 3), not bad input.
    throw new Error(`diverged: ${where}MuJoCo diverged while settling: there is no settled ` +
                    'state to read');
  }
  const warnings = [];
  for (let i = 0; i < mj.mjtWarning.mjNWARNING.value; ++i) {
    const n = d.warning.get(i).number;
    if (n > 0) warnings.push(`${mj.mju_warningText(i, d.warning.get(i).lastinfo)} (${n} times)`);
  }
  // <option> decoded here: its enums and flag bits are this version's.
  const disable = m.opt.disableflags, bits = mj.mjtDisableBit;
  const out = {
    version: mj.mj_versionString(),
    timestep: m.opt.timestep,
    integrator: integrators[m.opt.integrator] ?? `integrator ${m.opt.integrator}`,
    elliptic: m.opt.cone === mj.mjtCone.mjCONE_ELLIPTIC.value,
    impratio: m.opt.impratio,
    noslip_iterations: m.opt.noslip_iterations,
    gravity: Array.from(m.opt.gravity),
    refsafe: !(disable & bits.mjDSBL_REFSAFE.value),
    disabled: disable & bits.mjDSBL_CONTACT.value      ? 'contacts'
        : disable & bits.mjDSBL_CONSTRAINT.value ? 'constraints'
                                                 : '',
    settled: steps * m.opt.timestep,
    step_warnings: warnings,
    nv,
    body_names: Array.from({length: nbody}, (_, b) => nameAt(m, m.name_bodyadr[b])),
    geom_names: Array.from({length: ngeom}, (_, g) => nameAt(m, m.name_geomadr[g])),
    contacts: []
  };
  for (const key of ['body_weldid', 'body_parentid', 'body_mass', 'body_inertia',
                     'body_invweight0', 'jnt_bodyid', 'jnt_type', 'geom_bodyid', 'geom_condim',
                     'geom_contype', 'geom_conaffinity', 'geom_friction', 'geom_margin',
                     'geom_gap', 'geom_priority', 'geom_solmix', 'geom_solref', 'pair_geom1', 'pair_geom2', 'pair_margin', 'pair_gap']) {
    out[key] = Array.from(m[key]);
  }
  out.qvel = Array.from(d.qvel);
  out.qacc = Array.from(d.qacc);
  out.efc_force = Array.from(d.efc_force.slice(0, d.nefc));
  const jp = new mj.DoubleBuffer(3 * nv), jr = new mj.DoubleBuffer(3 * nv);
  const force = new mj.DoubleBuffer(6);
  // mj_jac's three translational rows of a body at a point, sparse.
  const jacobian = (pos, body) => {
    mj.mj_jac(m, d, jp, jr, pos, body);
    const j = jp.GetView();
    return [0, 1, 2].map((k) => sparse(j.subarray(k * nv, (k + 1) * nv)));
  };
  try {
    for (let i = 0; i < d.ncon; ++i) {
      const con = d.contact.get(i);
      const pos = Array.from(con.pos);
      mj.mj_contactForce(m, d, i, force);
      out.contacts.push({
        geom1: con.geom1,
        geom2: con.geom2,
        dim: con.dim,
        exclude: con.exclude,
        efc_address: con.efc_address,
        dist: con.dist,
        includemargin: con.includemargin,
        pos,
        frame: Array.from(con.frame),
        friction: Array.from(con.friction),
        solref: Array.from(con.solref),
        solreffriction: Array.from(con.solreffriction),
        solimp: Array.from(con.solimp),
        normal_force: force.GetView()[0],
        jac1: jacobian(pos, m.geom_bodyid[con.geom1]),
        jac2: jacobian(pos, m.geom_bodyid[con.geom2])
      });
    }
  } finally {
    for (const b of [jp, jr, force]) b.delete();
  }
  // The gravity load at this configuration, at rest: qfrc_bias at qvel = 0,
  // in the same mjData (as mujoco/model_state.cpp does).
  d.qvel.fill(0);
  mj.mj_forward(m, d);
  out.bias = Array.from(d.qfrc_bias);
  return out;
}

// M⁻¹ times each sparse row (mj_solveM at the state "read" left).
function solveRows(m, d, rows) {
  const nv = m.nv;
  const x = new mj.DoubleBuffer(nv);
  try {
    return rows.map((row) => {
      if (!Array.isArray(row.index) || !Array.isArray(row.value) ||
          row.index.length !== row.value.length) {
        throw new Error('solve: a row is not {index, value} of one length');
      }
      const dense = new Float64Array(nv);
      row.index.forEach((c, k) => {
        if (!Number.isInteger(c) || c < 0 || c >= nv) throw new Error(`solve: column ${c}`);
        dense[c] = row.value[k];
      });
      mj.mj_solveM(m, d, x, dense);
      return sparse(x.GetView());
    });
  } finally {
    x.delete();
  }
}

const ops = {
  hello: (r) => {
    if (r.protocol !== PROTOCOL) {
      throw new Error(`${join(here, 'driver.mjs')} speaks protocol ${PROTOCOL}, contact2d ` +
                      `${r.protocol}: CONTACT2D_MUJOCO3_DIR names another checkout's driver`);
    }
    return {
      version: mj.mj_versionString(),
      package: packageVersion,
      node: process.versions.node,
      protocol: PROTOCOL
    };
  },
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
    close(r.id);
    return {};
  },
  reset: (r) => {
    const e = entry(r.id);
    mj.mj_resetData(e.m, e.d);
    e.d.qpos.set(r.qpos);
    e.d.qvel.set(r.qvel);
    e.saved = null;
    return {};
  },
  applied: (r) => {
    const e = entry(r.id);
    e.d.xfrc_applied.set(r.xfrc, 6 * r.body);
    return {};
  },
  step: (r) => {
    const e = entry(r.id);
    const { m, d } = e;
    const nq = m.nq, nv = m.nv, width = nq + nv;
    if (!Number.isInteger(r.n) || r.n < 1 || r.n > 1 << 20) throw new Error(`step n = ${r.n}`);
    const out = new Float64Array(r.n * width);
    save(e);
    const before = badCounters(d);
    let steps = runSteps(e, out, r.n, before);
    const bad = before > 0 || badCounters(d) > before;
    if (bad && !e.found && before === 0) {
      // A counter rose at a step the cheap test did not look at (RK4's
      // qacc after the step is not the one MuJoCo tested): the batch again
      // from its start, the counters read after every step, to find it.
      restore(e);
      const now = badCounters(d);
      steps = 0;
      do {
        mj.mj_step(m, d);
        out.set(d.qpos, steps * width);
        out.set(d.qvel, steps * width + nq);
        ++steps;
      } while (badCounters(d) === now && steps < r.n);
    }
    const bytes = Buffer.from(out.buffer, 0, steps * width * 8);
    return { steps, bad, bytes: bytes.length, payload: bytes };
  },
  rewind: (r) => {
    const e = entry(r.id);
    if (!e.saved) throw new Error('rewind without a step');
    restore(e);
    for (let i = 0; i < r.n; ++i) mj.mj_step(e.m, e.d);
    return {};
  },
  open: (r) => {
    const where = r.option ? r.option + ' ' : '';
    const {m, stage, loadWarning} = compile(r.path, where);
    let d;
    try {
      d = new mj.MjData(m);
      const steps = prepareState(m, d, r);
      const handle = nextId++;
      models.set(handle, {m, d, saved: null, stage, request: r, steps, taken: 0, loadWarning});
      return {handle, steps};
    } catch (e) {
      if (d) d.delete();
      m.delete();
      stage.remove();
      throw e;
    }
  },
  settle: (r) => {
    const e = entry(r.handle);
    if (!Number.isInteger(r.n) || r.n < 0) throw new Error(`settle n = ${r.n}`);
    const until = performance.now() + r.ms;
    let done = 0;
    while (done < r.n && (done === 0 || performance.now() < until)) {
      mj.mj_step(e.m, e.d);
      ++done;
    }
    e.taken += done;
    return {done};
  },
  read: (r) => {
    const e = entry(r.handle);
    return {...readState(e.m, e.d, e.request, e.taken), load_warning: e.loadWarning};
  },
  solve: (r) => {
    const e = entry(r.handle);
    if (!Array.isArray(r.rows)) throw new Error('solve without rows');
    return {rows: solveRows(e.m, e.d, r.rows)};
  },
  close: (r) => {
    close(r.handle);
    return {};
  },
  counters: (r) => {
    const {d} = entry(r.id);
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
  const before = messages.length;
  try {
    const request = JSON.parse(line);
    const op = ops[request.op];
    if (!op) throw new Error(`unknown op ${request.op}`);
    answer = {ok: true, ...op(request)};
  } catch (e) {
    // What MuJoCo printed on the way ("Cannot enlarge memory ...") is part
    // of the error: its own text, not only the abort that followed.
    const said = messages.splice(before).map(oneLine).filter((t) => t);
    const text = oneLine(e);
    answer = {ok: false, error: said.length ? `${text} (MuJoCo: ${said.join('; ')})` : text};
    // An abort leaves the WebAssembly instance unusable: say so and end.
    if (e instanceof WebAssembly.RuntimeError || /^Aborted\(/.test(text)) answer.fatal = true;
  }
  const payload = answer.payload;
  delete answer.payload;
  if (messages.length) answer.messages = messages.splice(0).map(oneLine);
  process.stdout.write(JSON.stringify(answer) + '\n');
  if (payload) process.stdout.write(payload);
  if (answer.fatal) process.stdout.write('', () => process.exit(3));
});
input.on('close', () => process.exit(0));
