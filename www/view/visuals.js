// A robot's <visual> as a three.js object (bundled with three-view.js):
// a mesh file through three's own loaders (STL, OBJ, Collada), a box, a
// cylinder or a sphere, in the URDF's colour or a light grey; and the
// core's rotations (by rows) as three's matrices.

import { BoxGeometry, Color, CylinderGeometry, Matrix4, Mesh, MeshStandardMaterial, SphereGeometry } from 'three';
import { STLLoader } from 'three/addons/loaders/STLLoader.js';
import { OBJLoader } from 'three/addons/loaders/OBJLoader.js';
import { ColladaLoader } from 'three/addons/loaders/ColladaLoader.js';

const decoder = new TextDecoder();
/** A <visual>'s object, or null where its mesh is not at hand or does not parse. */
export function visualObject(v, meshes) {
  const rgba = v.colour ?? [0.78, 0.8, 0.83, 1];
  const material = new MeshStandardMaterial({ color: new Color(rgba[0], rgba[1], rgba[2]), roughness: 0.6, metalness: 0.1, transparent: rgba[3] < 1, opacity: rgba[3] });
  const g = v.geometry;
  if (g.box) return new Mesh(new BoxGeometry(...g.box), material);
  if (g.sphere) return new Mesh(new SphereGeometry(g.sphere, 24, 16), material);
  if (g.cylinder) return new Mesh(new CylinderGeometry(g.cylinder[0], g.cylinder[0], g.cylinder[1], 24).rotateX(Math.PI / 2), material);
  // Keyed by the name as the URDF gives it (robot-open.js's resolveMeshes); by its file name as a fallback.
  const name = g.mesh.split(/[\\/]/).pop();
  const bytes = meshes[g.mesh] ?? meshes[name];
  if (!bytes) return null;
  let object = null;
  try {
    if (/\.stl$/i.test(name)) {
      // Many writers leave a facet's normal zero: the normals are taken from the triangles.
      const geometry = new STLLoader().parse(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength));
      geometry.computeVertexNormals();
      object = new Mesh(geometry, material);
    }
    else if (/\.obj$/i.test(name)) {
      object = new OBJLoader().parse(decoder.decode(bytes));
      object.traverse((o) => {
        if (o.isMesh) o.material = material;
      });
    } else if (/\.dae$/i.test(name)) {
      // Collada: the loader turns a Z-up file Y-up; the URDF's frames are the file's own.
      object = new ColladaLoader().parse(decoder.decode(bytes), '').scene;
      object.rotation.set(0, 0, 0);
      const strays = [];
      object.traverse((o) => (o.isCamera || o.isLight) && strays.push(o));
      for (const o of strays) o.removeFromParent();
      if (v.colour) object.traverse((o) => o.isMesh && (o.material = material));
    }
  } catch (_) {
    return null;
  }
  if (object) object.scale.set(...g.scale);
  return object;
}


const rows = new Matrix4();
/**
 * The core's rotation matrix `r` (three rows of three, SceneView's
 * target_rotation and hand_rotation) as a three.js Matrix4 (one shared
 * instance: read it before the next call).
 */
export function byRows(r) {
  return rows.set(r[0][0], r[0][1], r[0][2], 0, r[1][0], r[1][1], r[1][2], 0, r[2][0], r[2][1], r[2][2], 0, 0, 0, 0, 1);
}
