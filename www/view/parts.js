// The 3-D view's small drawing parts (bundled with three-view.js): a
// line through points whose buffer grows when needed, a pool of meshes,
// a unit cylinder placed between two points.

import { BufferGeometry, Float32BufferAttribute, Quaternion, Vector3 } from 'three';

const UP = new Vector3(0, 1, 0);

/** A line's geometry through flat points, its buffer grown when needed. */
export function setPoints(line, points, dashed = false) {
  const n = points.length;
  let geom = line.geometry;
  const attr = geom.getAttribute('position');
  if (!attr || attr.count < n) {
    geom.dispose();
    geom = new BufferGeometry();
    geom.setAttribute('position', new Float32BufferAttribute(new Float32Array(Math.max(n, 16) * 3), 3));
    line.geometry = geom;
  }
  const a = geom.getAttribute('position');
  for (let i = 0; i < n; i++) a.setXYZ(i, points[i][0], points[i][1], points[i][2]);
  a.needsUpdate = true;
  geom.setDrawRange(0, n);
  geom.computeBoundingSphere();
  if (dashed) line.computeLineDistances();
  line.visible = n > 1;
}

/** A pool of meshes made by `make`, as many shown as asked. */
export function pool(parent, make) {
  const items = [];
  return (n) => {
    while (items.length < n) {
      const m = make();
      parent.add(m);
      items.push(m);
    }
    items.forEach((m, i) => (m.visible = i < n));
    return items;
  };
}

// The cylinder's scratch vectors: placing one allocates nothing.
const start = new Vector3();
const along = new Vector3();
const NONE = new Quaternion();

/** Places a unit cylinder (along y, height 1) from `a` to `b` with radius `r`. */
export function placeCylinder(mesh, a, b, r) {
  start.set(a[0], a[1], a[2]);
  along.set(b[0], b[1], b[2]).sub(start);
  const len = along.length();
  mesh.position.copy(start).addScaledVector(along, 0.5);
  if (len > 1e-12) mesh.quaternion.setFromUnitVectors(UP, along.divideScalar(len));
  else mesh.quaternion.copy(NONE);
  mesh.scale.set(r, Math.max(len, 1e-9), r);
}
