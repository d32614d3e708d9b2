// A robot of the user's: "Open robot…" takes a .urdf file with the mesh
// files it names (several files, a folder, or a .zip: pkg/unzip.js), and
// `urdf=URL` (with `base`, `tip`) fetches them from a host that allows it;
// the workers' module reads them (readRobot, src/web/robot.rs: the URDF
// reader stays out of the page's module) into the chain SpaceDemo.ofChain
// runs. The files are kept in this browser's IndexedDB under their content
// hash (SHA-256 of the URDF and the meshes, 16 hex digits), and the page
// opens `?robot=HASH`: a reload, or the same link in this browser, opens
// the robot again. A run file carries the chain itself, so `simulate
// --from` replays a run of it on any machine.

import { runWorker } from './jobs.js';
import { moduleVersion } from './module.js';

const DB = 'redundant-ik-robots';
const STORE = 'robots';
/** Largest URDF, and all files together, the page takes (bytes): the reader's own limit is 8 MB a URDF. */
const MAX_URDF = 8 << 20;
const MAX_TOTAL = 64 << 20;
/** The hash an address names: 16 hexadecimal digits. */
export const ROBOT_HASH = /^[0-9a-f]{16}$/;

function database() {
  return new Promise((resolve, reject) => {
    const open = indexedDB.open(DB, 1);
    open.onupgradeneeded = () => open.result.createObjectStore(STORE);
    open.onsuccess = () => resolve(open.result);
    open.onerror = () => reject(new Error(`this browser's storage refused to open (${open.error?.message ?? 'IndexedDB'})`));
  });
}

async function transact(mode, fn) {
  const db = await database();
  try {
    return await new Promise((resolve, reject) => {
      const tx = db.transaction(STORE, mode);
      const req = fn(tx.objectStore(STORE));
      tx.oncomplete = () => resolve(req?.result);
      tx.onerror = () => reject(new Error(`this browser's storage failed: ${tx.error?.message ?? 'IndexedDB'}`));
    });
  } finally {
    db.close();
  }
}

/** The stored robot `hash` ({ name, urdf, meshes: { name: Uint8Array }, base, tip }), or null. */
export async function storedRobot(hash) {
  if (!ROBOT_HASH.test(hash)) return null;
  return (await transact('readonly', (s) => s.get(hash))) ?? null;
}

/** The content hash of a robot's files: 16 hex digits of SHA-256 over the URDF and each mesh's name and bytes. */
async function contentHash(urdf, meshes) {
  const enc = new TextEncoder();
  const parts = [enc.encode(urdf)];
  for (const name of Object.keys(meshes).sort()) parts.push(enc.encode(`\0${name}\0`), meshes[name]);
  const all = new Uint8Array(parts.reduce((n, p) => n + p.length, 0));
  let at = 0;
  for (const p of parts) {
    all.set(p, at);
    at += p.length;
  }
  const digest = new Uint8Array(await crypto.subtle.digest('SHA-256', all));
  return [...digest.slice(0, 8)].map((b) => b.toString(16).padStart(2, '0')).join('');
}

/**
 * The robot's files read by the workers' module: resolves to readRobot's
 * result ({ name, base, tip, chain, joints, volumes, warnings }) or
 * rejects with the reader's message.
 */
export async function readRobot({ urdf, meshes, base, tip }) {
  const { result } = await runWorker({ kind: 'robot', urdf, meshes, base: base || null, tip: tip || null });
  return result;
}

/** A file name's last part, `/` or `\\` separated. */
const lastPart = (path) => path.split(/[\\/]/).pop();

/** The chosen files as entries { name, path, bytes }: a .zip unpacked (pkg/unzip.js, fflate), a folder's files with their paths. */
async function entriesOf(files) {
  const out = [];
  for (const f of files) {
    if (/\.zip$/i.test(f.name)) {
      const { unzipRobot } = await import('./pkg/unzip.js');
      const unpacked = unzipRobot(new Uint8Array(await f.arrayBuffer()), MAX_TOTAL);
      for (const [path, bytes] of Object.entries(unpacked)) out.push({ name: lastPart(path), path, bytes });
    } else if (/\.(urdf|xml|stl|dae|obj)$/i.test(f.name)) {
      out.push({ name: f.name, path: f.webkitRelativePath || f.name, bytes: new Uint8Array(await f.arrayBuffer()) });
    }
  }
  return out;
}

/** Every mesh file name a URDF's <mesh> elements give (collision and visual). */
function meshNames(urdf) {
  const doc = new DOMParser().parseFromString(urdf, 'application/xml');
  return [...new Set([...doc.getElementsByTagName('mesh')].map((m) => m.getAttribute('filename')).filter(Boolean))];
}

/**
 * The bytes of each mesh a URDF names, keyed by the name as the URDF gives
 * it: the entry whose path ends with the name's path (after `package://PKG/`
 * or `file://`), else the one with the same file name.
 */
export function resolveMeshes(urdf, entries) {
  const meshes = {};
  for (const name of meshNames(urdf)) {
    const rest = name.replace(/^package:\/\/[^/]*\//, '').replace(/^file:\/\//, '').replace(/\\/g, '/');
    const path = (e) => e.path.replace(/\\/g, '/');
    const hit = entries.find((e) => path(e).endsWith(rest) || rest.endsWith(path(e))) ?? entries.find((e) => e.name === lastPart(rest));
    if (hit) meshes[name] = hit.bytes;
  }
  return meshes;
}

/**
 * The files a person chose (a .urdf and its meshes, a folder of them, or a
 * .zip): read, checked by the reader, stored; resolves to { hash, read }.
 * Rejects with a message that says what is wrong (no URDF, two, too large,
 * the reader's own).
 */
export async function openFiles(files, { base, tip } = {}) {
  const list = [...files];
  const total = list.reduce((n, f) => n + f.size, 0);
  if (total > MAX_TOTAL) throw new Error(`the files have ${total} bytes together, more than the ${MAX_TOTAL} the page takes`);
  const entries = await entriesOf(list);
  const decoder = new TextDecoder();
  // The URDF: the one .urdf, else the one .xml that is a <robot> (a ROS package's package.xml is not).
  let urdfs = entries.filter((e) => /\.urdf$/i.test(e.name));
  if (!urdfs.length) urdfs = entries.filter((e) => /\.xml$/i.test(e.name) && /<robot[\s>]/.test(decoder.decode(e.bytes.subarray(0, 4096))));
  if (urdfs.length !== 1) throw new Error(urdfs.length ? `${urdfs.length} URDF files were chosen (${urdfs.map((f) => f.path).join(', ')}): choose one, with its mesh files` : "no .urdf file was chosen: choose the robot's .urdf with its mesh files, a folder or a .zip of them");
  if (urdfs[0].bytes.length > MAX_URDF) throw new Error(`${urdfs[0].name} has ${urdfs[0].bytes.length} bytes, more than the ${MAX_URDF} a URDF may have`);
  const urdf = decoder.decode(urdfs[0].bytes);
  return keep({ urdf, entries, base, tip, file: urdfs[0].name });
}

/** A robot's URDF and its files read by the reader and stored; { hash, read }. */
async function keep({ urdf, entries, base, tip, file, url = null }) {
  const meshes = resolveMeshes(urdf, entries);
  const read = await readRobot({ urdf, meshes, base, tip });
  const hash = await contentHash(urdf, meshes);
  // The reading is kept too, stamped with the version that made it: the page opened next uses it without reading again.
  await transact('readwrite', (s) => s.put({ name: read.name, urdf, meshes, base: base || null, tip: tip || null, file, url, read, version: moduleVersion() }, hash));
  return { hash, read };
}

/**
 * A robot fetched from `url` (`urdf=URL` in the address), with the meshes
 * its URDF names fetched beside it (a `package://PKG/REST` as REST under the
 * URDF's folder and its parent, a relative name under its folder); kept and
 * read as a chosen file is. A host that does not allow this page to read
 * its files (CORS) is named in the refusal.
 */
export async function openUrl(url, { base, tip } = {}) {
  const get = async (u) => {
    let r;
    try {
      r = await fetch(u);
    } catch (_) {
      throw new Error(`${u} could not be fetched: its host is not reachable, or does not allow this page to read it (it sends no Access-Control-Allow-Origin header: CORS)`);
    }
    if (!r.ok) throw new Error(`${u}: HTTP ${r.status}`);
    return new Uint8Array(await r.arrayBuffer());
  };
  const bytes = await get(url);
  if (bytes.length > MAX_URDF) throw new Error(`${url} has ${bytes.length} bytes, more than the ${MAX_URDF} a URDF may have`);
  const urdf = new TextDecoder().decode(bytes);
  const entries = [];
  // The meshes together may not pass what the page takes of files chosen.
  let total = bytes.length;
  for (const name of meshNames(urdf)) {
    const rest = name.replace(/^package:\/\/[^/]*\//, '');
    // A package's meshes usually sit beside its urdf/ folder: the parent first.
    const tries = /^package:/.test(name) ? [new URL(`../${rest}`, url), new URL(rest, url)] : /^[a-z]+:/i.test(name) ? [] : [new URL(name, url)];
    for (const u of tries) {
      const got = await get(u.href).catch(() => null);
      if (got && (total += got.length) > MAX_TOTAL) throw new Error(`${url} and its meshes have more than the ${MAX_TOTAL} bytes the page takes`);
      if (got) {
        entries.push({ name: lastPart(rest), path: rest, bytes: got });
        break;
      }
    }
  }
  return keep({ urdf, entries, base, tip, file: lastPart(new URL(url).pathname), url });
}

/**
 * The page's options for the stored robot `hash` (`?robot=HASH`): { hash,
 * chain, read, preset } (`preset` what the page in space reads of a
 * shipped arm's: key, label, source, its own task filled in by the page),
 * or a rejection that says why (not in this browser's storage, or the
 * reader's message).
 */
export async function openStored(hash) {
  if (!ROBOT_HASH.test(String(hash))) throw new Error(`'${String(hash).slice(0, 40)}' is not a robot's hash (16 hexadecimal digits, as "Open robot…" writes it)`);
  const record = await storedRobot(hash);
  if (!record) throw new Error(`the robot ${hash} is not in this browser's storage (robots opened here are kept where they were opened): open its URDF again with "Open robot…"`);
  // The reading kept with the files, where this version made it; else read again (in a worker).
  const read = record.read && record.version === moduleVersion() ? record.read : await readRobot(record);
  const visuals = visualsOf(record.urdf);
  const preset = {
    key: 'robot',
    label: read.name,
    source: `your URDF ${record.url ?? record.file ?? ''}, ${read.joints.length} joints from ${read.base} to ${read.tip}, kept in this browser as ${hash}`,
    // Fetched from an address: the link names it (any browser fetches it again); else the browser's own copy.
    address: record.url ? [['urdf', record.url], ...(record.base ? [['base', record.base]] : []), ...(record.tip ? [['tip', record.tip]] : [])] : [['robot', hash]],
    rate_limits: null,
    task: null,
  };
  // The URDF and the links asked for travel in the robot's run files, as `simulate --urdf FILE --json` writes them.
  return { hash, chain: read.chain, read, preset, visuals, meshes: record.meshes, urdf: record.urdf, base: record.base, tip: record.tip };
}

const numbers = (text, n, fallback) => {
  const v = (text ?? '').trim().split(/\s+/).map(Number);
  return v.length === n && v.every(Number.isFinite) ? v : fallback;
};

/**
 * The `<visual>` elements of a URDF's links, for the 3-D view: `[{ link,
 * xyz, rpy, geometry: { mesh, scale } | { box } | { cylinder: [r, l] } |
 * { sphere }, colour }]`. Read by the browser's XML parser after the core's
 * reader accepted the file (it refuses a document type declaration); what
 * does not parse is left out (the link is then drawn by its capsules).
 */
export function visualsOf(urdf) {
  const doc = new DOMParser().parseFromString(urdf, 'application/xml');
  if (doc.querySelector('parsererror')) return [];
  const robot = doc.documentElement;
  const named = new Map();
  for (const m of robot.children) {
    if (m.tagName !== 'material') continue;
    const c = m.querySelector('color')?.getAttribute('rgba');
    if (c) named.set(m.getAttribute('name'), numbers(c, 4, null));
  }
  const out = [];
  for (const link of robot.children) {
    if (link.tagName !== 'link') continue;
    for (const v of link.children) {
      if (v.tagName !== 'visual') continue;
      const origin = [...v.children].find((c) => c.tagName === 'origin');
      const g = [...v.children].find((c) => c.tagName === 'geometry')?.firstElementChild;
      if (!g) continue;
      const geometry =
        g.tagName === 'mesh' ? { mesh: g.getAttribute('filename') ?? '', scale: numbers(g.getAttribute('scale'), 3, [1, 1, 1]) }
        : g.tagName === 'box' ? { box: numbers(g.getAttribute('size'), 3, null) }
        : g.tagName === 'cylinder' ? { cylinder: [Number(g.getAttribute('radius')), Number(g.getAttribute('length'))] }
        : g.tagName === 'sphere' ? { sphere: Number(g.getAttribute('radius')) }
        : null;
      if (!geometry || Object.values(geometry).some((x) => x === null || (typeof x === 'number' && !Number.isFinite(x)))) continue;
      const m = [...v.children].find((c) => c.tagName === 'material');
      const rgba = m?.querySelector('color')?.getAttribute('rgba');
      out.push({
        link: link.getAttribute('name'),
        xyz: numbers(origin?.getAttribute('xyz'), 3, [0, 0, 0]),
        rpy: numbers(origin?.getAttribute('rpy'), 3, [0, 0, 0]),
        geometry,
        colour: (rgba ? numbers(rgba, 4, null) : named.get(m?.getAttribute('name'))) ?? null,
      });
    }
  }
  return out;
}

/** What the reader made of a robot, as a few lines for the page (the chain, its joints and limits, the volumes, the warnings). */
export function describeRobot(read) {
  const deg = (v) => `${Math.round((v * 180) / Math.PI)}°`;
  const joints = read.joints.map((j) => {
    const range = j.limits ? (j.kind === 'prismatic' ? `${j.limits[0]} to ${j.limits[1]} m` : `${deg(j.limits[0])} to ${deg(j.limits[1])}`) : 'no limits';
    return `${j.name} (${j.kind}, ${range})`;
  });
  const meshes = read.volumes.filter((v) => v.source.startsWith('mesh')).length;
  return [
    `${read.name}: ${read.joints.length} moving joints from ${read.base} to ${read.tip}.`,
    `Joints: ${joints.join('; ')}.`,
    `Collision volumes: ${read.volumes.length} capsules (${meshes} fitted around meshes), radius ${Math.min(...read.volumes.map((v) => v.radius)).toFixed(3)} to ${Math.max(...read.volumes.map((v) => v.radius)).toFixed(3)} m.`,
    ...read.warnings.map((w) => `Warning: ${w}`),
  ];
}
