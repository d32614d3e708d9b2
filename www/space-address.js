// The address of a scene in space (arm=panda or arm=iiwa14; robot=HASH, a
// robot of the user's kept in this browser: robot-open.js): what it asks
// for, and the state written back into it. Keys: arm, method, lambda and
// the methods' other parameters by name, target=X,Y,Z (or
// X,Y,Z,ROLL,PITCH,YAW, rad: the hand's full pose, as task=pose),
// orientation_weight (Z's z),
// obstacles=X,Y,Z,R;X,Y,Z,R (the spheres, m), feedback, weighting, floor,
// self_collision (1: the links kept apart from each other),
// damping (1: the schedule near singular poses on; off by default in
// space), theta0 (the start pose, rad: self-motion moves it), path (the
// core's syntax: line, circle:CX,CY,CZ,NX,NY,NZ[,LAPS], points:X,Y,Z;...),
// networks, precision (the networks' arithmetic: f64 or f32),
// view=YAW,PITCH,DISTANCE (degrees, degrees, m), embed and
// projector as the plane's address has them (address.js). Numbers are
// checked by the module; what does not parse here is returned as a
// problem and shown, the rest applied.

import { params, spacePresets, limits, precisions, readPrecision } from './module.js';

/**
 * The spatial preset an address names (`arm=panda`; `arm=space`: the first
 * of them, what the planar page's designer opens), or null.
 */
export function spaceArmOf(search) {
  const arm = new URLSearchParams(search).get('arm');
  if (!arm) return null;
  if (arm === 'space') return spacePresets()[0].key;
  return spacePresets().some((p) => p.key === arm) ? arm : null;
}

const numbers = (text, count) => {
  const v = text.split(',').map((x) => Number(x.trim()));
  if (v.length !== count || v.some((x) => !Number.isFinite(x))) throw new Error(`expected ${count} numbers separated by commas`);
  return v;
};

/** The settings of a spatial address, and its problems (`key: why`). */
export function readSpaceAddress(search) {
  const q = new URLSearchParams(search);
  const problems = [];
  const read = (key, parse) => {
    const v = q.get(key);
    if (v === null) return undefined;
    try {
      return parse(v);
    } catch (e) {
      problems.push(`${key}: ${e.message}`);
      return undefined;
    }
  };
  const settings = {
    arm: spaceArmOf(search),
    method: q.get('method') ?? q.get('mode') ?? undefined,
    task: q.get('task') ?? undefined,
    // x, y, z (m), or the hand's full pose with roll, pitch, yaw (rad).
    target: read('target', (v) => numbers(v, v.split(',').length === 6 ? 6 : 3)),
    orientation_weight: read('orientation_weight', (v) => numbers(v, 1)[0]),
    obstacles: read('obstacles', (v) => v.split(';').filter((x) => x.trim()).flatMap((x) => numbers(x, 4))),
    feedback: read('feedback', (v) => numbers(v, 1)[0]),
    weighting: q.get('weighting') ?? undefined,
    floor: q.has('floor') ? q.get('floor') === '1' : undefined,
    self_collision: q.has('self_collision') ? q.get('self_collision') === '1' : undefined,
    damping: q.has('damping') ? q.get('damping') === '1' : undefined,
    path: q.get('path') ?? undefined,
    theta0: read('theta0', (v) => v.split(',').map((x) => {
      const n = Number(x.trim());
      if (x.trim() === '' || !Number.isFinite(n)) throw new Error('expected the joint angles (rad) separated by commas');
      return n;
    })),
    precision: read('precision', readPrecision),
    view: read('view', (v) => numbers(v, 3)),
    projector: q.get('projector') === '1' || undefined,
    autoplay: q.has('autoplay') ? q.get('autoplay') !== '0' : undefined,
    params: {},
  };
  for (const p of params()) {
    const v = read(p.name, (x) => numbers(x, 1)[0]);
    if (v !== undefined) settings.params[p.name] = v;
  }
  return { ...settings, problems };
}

const exact = (v) => String(Math.round(v * 1e4) / 1e4);

/** The query of spatial state `s` (what "Copy link" and the Embed snippets give). */
export function spaceQuery(s, preset) {
  const q = new URLSearchParams();
  // A robot of the user's is named by its files' hash (robot-open.js).
  for (const [key, value] of preset.address ?? [['arm', s.arm]]) q.set(key, value);
  q.set('method', s.method);
  if (s.task === 'pose') {
    // The full pose: the target's orientation always (its start differs with theta0), its angles exact.
    q.set('target', [...s.target.map(exact), ...s.target_rpy.map(String)].join(','));
    if (s.orientation_weight !== 1) q.set('orientation_weight', String(s.orientation_weight));
  } else if (s.target.some((v, i) => Math.abs(v - preset.task.target[i]) > 1e-9)) q.set('target', s.target.map(exact).join(','));
  const own = preset.task.sphere;
  const same = own ? s.spheres.length === 1 && s.spheres[0].every((v, i) => Math.abs(v - own[i]) < 1e-9) : s.spheres.length === 0;
  if (!same) q.set('obstacles', s.spheres.map((sp) => sp.map(exact).join(',')).join(';'));
  if (s.feedback > 0) q.set('feedback', String(s.feedback));
  if (s.weighting !== limits().joint_weightings[0][0]) q.set('weighting', s.weighting);
  if (s.floor) q.set('floor', '1');
  if (s.self_collision) q.set('self_collision', '1');
  if (s.damping) q.set('damping', '1');
  if (s.path) q.set('path', s.path);
  // A start of the user's own (self-motion moves it), its angles exact.
  if (s.theta0.some((v, i) => Math.abs(v - preset.task.theta0[i]) > 1e-12)) q.set('theta0', s.theta0.map(String).join(','));
  if (s.precision !== precisions()[0].name) q.set('precision', s.precision);
  for (const p of params()) {
    if (s.params[p.name] !== undefined && s.params[p.name] !== p.default) q.set(p.name, String(s.params[p.name]));
  }
  const [yaw, pitch, d] = s.view;
  q.set('view', [(yaw * 180) / Math.PI, (pitch * 180) / Math.PI, d].map((v) => String(Math.round(v * 10) / 10)).join(','));
  return q;
}

/** Writes `s` into the page's address (history.replaceState); returns it. */
export function writeSpaceAddress(s, preset) {
  const q = spaceQuery(s, preset);
  const here = new URLSearchParams(location.search);
  if (here.get('embed') === '1') q.set('embed', '1');
  if (document.documentElement.hasAttribute('data-projector')) q.set('projector', '1');
  history.replaceState(null, '', `${location.pathname}?${q}`);
  return location.href;
}
