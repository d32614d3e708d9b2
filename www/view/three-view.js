// The 3-D view of an arm in space, drawn by three.js (MIT; pinned in
// tools/package.json). Not loaded as it is: `make web` bundles it with
// three into pkg/three-view.js (tools/bundle.mjs view), which space-view.js
// imports only when an arm in space is shown, so the planar page loads no
// byte of it.
//
// It computes no position: every frame draws what the core's
// SpaceDemo.view() says (src/web/space_stage.rs, SceneView): the camera
// (the same projection as the overlay's and the pointer's), the links as
// capsules of the chain's radius, the joints, the spheres, the floor and
// its grid with the shadows on it, the dashed path, the hand's trail, the
// numerical ghost, the ellipsoids at the hand and a slice atlas on its
// plane (SpaceDemo.layerView()). The target's handle, the keyboard's ring,
// the axis cross and the caption are the overlay's, the 2-D canvas above.

import {
  AxesHelper,
  BufferGeometry,
  CylinderGeometry,
  DirectionalLight,
  DoubleSide,
  Float32BufferAttribute,
  Group,
  HemisphereLight,
  Line,
  LineBasicMaterial,
  LineDashedMaterial,
  LineLoop,
  Mesh,
  MeshBasicMaterial,
  MeshStandardMaterial,
  PCFShadowMap,
  BasicShadowMap,
  PerspectiveCamera,
  PlaneGeometry,
  Quaternion,
  Scene,
  ShadowMaterial,
  SphereGeometry,
  WebGLRenderer,
  Color,
  LineSegments,
  Euler,
  Matrix4,
} from 'three';
import { TransformControls } from 'three/addons/controls/TransformControls.js';
import { visualObject, byRows } from './visuals.js';
import { setPoints, pool, placeCylinder } from './parts.js';

/**
 * Whether the browser's WebGL draws on the CPU (SwiftShader, llvmpipe: no
 * GPU, or the GPU blocked), asked of a throwaway context. There the view
 * draws without multisampling and with plain shadows: in headless Chromium
 * on this project's machines (SwiftShader) that took dragging the Panda's
 * target from 15 to 28 frames a second (scripts/view-fps.mjs, docs/web.md).
 */
function softwareGl() {
  const gl = document.createElement('canvas').getContext('webgl2');
  if (!gl) return false;
  const info = gl.getExtension('WEBGL_debug_renderer_info');
  const name = info ? String(gl.getParameter(info.UNMASKED_RENDERER_WEBGL)) : '';
  gl.getExtension('WEBGL_lose_context')?.loseContext();
  return /swiftshader|llvmpipe|software/i.test(name);
}

/**
 * The view on `canvas` (a <canvas> for WebGL), in the page's `palette`
 * ({ arm, ink, danger, ... }: the module's colours). Throws where the
 * browser gives no WebGL.
 */
export function createView(canvas, palette) {
  const software = softwareGl();
  const renderer = new WebGLRenderer({ canvas, antialias: !software, alpha: false });
  renderer.setClearColor(new Color('#ffffff'), 1);
  renderer.shadowMap.enabled = true;
  renderer.shadowMap.type = software ? BasicShadowMap : PCFShadowMap;
  const scene = new Scene();
  const camera = new PerspectiveCamera(40, 1, 0.05, 60);
  camera.up.set(0, 0, 1);

  scene.add(new HemisphereLight(0xffffff, 0xb0b8c0, 1.6));
  const sun = new DirectionalLight(0xffffff, 1.8);
  sun.position.set(0.6, 0.4, 3);
  sun.castShadow = true;
  sun.shadow.mapSize.setScalar(software ? 512 : 1024);
  Object.assign(sun.shadow.camera, { left: -1.5, right: 1.5, top: 1.5, bottom: -1.5, near: 0.1, far: 6 });
  sun.shadow.bias = -0.0005;
  scene.add(sun, sun.target);

  // The floor: its shadows, its grid (z = 0), its axes darker.
  const floor = new Mesh(new PlaneGeometry(1, 1), new ShadowMaterial({ opacity: 0.16 }));
  floor.receiveShadow = true;
  scene.add(floor);
  const grid = new LineSegments(new BufferGeometry(), new LineBasicMaterial({ color: palette.grid }));
  const gridAxes = new LineSegments(new BufferGeometry(), new LineBasicMaterial({ color: palette.axis }));
  scene.add(grid, gridAxes);
  let floorSize = null;
  const setFloor = ([half, step]) => {
    if (floorSize === `${half},${step}`) return;
    floorSize = `${half},${step}`;
    floor.scale.set(2 * half, 2 * half, 1);
    const lines = [];
    const axes = [];
    const n = Math.round((2 * half) / step);
    for (let k = 0; k <= n; k++) {
      const c = -half + k * step;
      (Math.abs(c) < 1e-9 ? axes : lines).push(c, -half, 0, c, half, 0, -half, c, 0, half, c, 0);
    }
    grid.geometry.setAttribute('position', new Float32BufferAttribute(lines, 3));
    gridAxes.geometry.setAttribute('position', new Float32BufferAttribute(axes, 3));
  };

  // The base plate, the arm's capsules and joints.
  const plate = new Mesh(new CylinderGeometry(1, 1, 1, 32), new MeshStandardMaterial({ color: palette.post, roughness: 0.8 }));
  plate.rotation.x = Math.PI / 2;
  plate.receiveShadow = true;
  scene.add(plate);
  const arm = new Group();
  scene.add(arm);
  const armMaterial = new MeshStandardMaterial({ color: palette.arm, roughness: 0.55, metalness: 0.05 });
  const jointMaterial = new MeshStandardMaterial({ color: palette.post, roughness: 0.6 });
  const cylinder = new CylinderGeometry(1, 1, 1, 24, 1, true);
  const ball = new SphereGeometry(1, 24, 16);
  const shadowed = (m) => {
    m.castShadow = true;
    m.receiveShadow = true;
    return m;
  };
  const links = pool(arm, () => shadowed(new Mesh(cylinder, armMaterial)));
  const ends = pool(arm, () => shadowed(new Mesh(ball, armMaterial)));
  const joints = pool(arm, () => new Mesh(ball, jointMaterial));

  // The spheres: see-through, deeper red while a link is inside one.
  const sphereMaterial = new MeshStandardMaterial({ color: palette.danger, transparent: true, opacity: 0.3, roughness: 0.4, depthWrite: false });
  const spheres = pool(scene, () => shadowed(new Mesh(ball, sphereMaterial)));

  // The path, the trail, the ghost.
  const path = new Line(new BufferGeometry(), new LineDashedMaterial({ color: palette.muted, dashSize: 0.02, gapSize: 0.015 }));
  const trail = new Line(new BufferGeometry(), new LineBasicMaterial({ color: palette.accent }));
  const ghost = new Line(new BufferGeometry(), new LineDashedMaterial({ color: palette.ghost, dashSize: 0.03, gapSize: 0.02, depthTest: false, transparent: true }));
  ghost.renderOrder = 2;
  const ghostJoints = pool(scene, () => {
    const m = new Mesh(ball, new MeshBasicMaterial({ color: palette.ghost, depthTest: false, transparent: true, opacity: 0.9 }));
    m.renderOrder = 2;
    return m;
  });
  scene.add(path, trail, ghost);

  // Self-collision: each checked pair of links near each other as the
  // segment between their closest points, red where they overlap; drawn
  // through the links.
  const selfNear = new LineSegments(new BufferGeometry(), new LineBasicMaterial({ vertexColors: true, depthTest: false, transparent: true }));
  selfNear.name = 'self near';
  selfNear.renderOrder = 3;
  scene.add(selfNear);
  const [near, overlap] = [new Color(palette.damper), new Color(palette.danger)];
  const setSelfNear = (pairs) => {
    selfNear.visible = pairs.length > 0;
    if (!pairs.length) return;
    const position = new Float32Array(pairs.length * 6);
    const colour = new Float32Array(pairs.length * 6);
    pairs.forEach((p, k) => {
      position.set([...p.points[0], ...p.points[1]], 6 * k);
      const c = p.distance < 0 ? overlap : near;
      colour.set([c.r, c.g, c.b, c.r, c.g, c.b], 6 * k);
    });
    selfNear.geometry.dispose();
    selfNear.geometry = new BufferGeometry();
    selfNear.geometry.setAttribute('position', new Float32BufferAttribute(position, 3));
    selfNear.geometry.setAttribute('color', new Float32BufferAttribute(colour, 3));
  };

  // The ellipsoids at the hand: each as its three principal ellipses.
  const ellipses = { velocity: [], force: [] };
  for (const [key, colour] of [['velocity', palette.velocity], ['force', palette.force]]) {
    for (let k = 0; k < 3; k++) {
      const l = new LineLoop(new BufferGeometry(), new LineBasicMaterial({ color: colour }));
      ellipses[key].push(l);
      scene.add(l);
    }
  }
  const setEllipsoid = (key, e, hand) => {
    const rings = ellipses[key];
    for (let k = 0; k < 3; k++) rings[k].visible = Boolean(e);
    if (!e) return;
    [[0, 1], [0, 2], [1, 2]].forEach(([a, b], k) => {
      const pts = [];
      for (let i = 0; i < 64; i++) {
        const t = (i / 64) * 2 * Math.PI;
        const u = e.half[a] * Math.cos(t);
        const w = e.half[b] * Math.sin(t);
        pts.push([0, 1, 2].map((j) => hand[j] + u * e.axes[a][j] + w * e.axes[b][j]));
      }
      setPoints(rings[k], pts);
    });
  };

  // A slice atlas on its plane: one quad a cell in its class's colour.
  const layer = new Mesh(new BufferGeometry(), new MeshBasicMaterial({ vertexColors: true, transparent: true, opacity: 0.42, side: DoubleSide, depthWrite: false }));
  layer.visible = false;
  scene.add(layer);
  let layerRevision = 0;
  const setLayer = (cells) => {
    layer.visible = Boolean(cells);
    if (!cells) return;
    const n = cells.colours.length;
    const position = new Float32Array(n * 18);
    const colour = new Float32Array(n * 18);
    const c = new Color();
    for (let k = 0; k < n; k++) {
      const q = cells.corners.slice(12 * k, 12 * k + 12);
      // Two triangles: corners 0 1 2 and 0 2 3.
      [0, 1, 2, 0, 2, 3].forEach((v, i) => position.set(q.slice(3 * v, 3 * v + 3), 18 * k + 3 * i));
      c.set(cells.colours[k]);
      for (let i = 0; i < 6; i++) colour.set([c.r, c.g, c.b], 18 * k + 3 * i);
    }
    layer.geometry.dispose();
    layer.geometry = new BufferGeometry();
    layer.geometry.setAttribute('position', new Float32BufferAttribute(position, 3));
    layer.geometry.setAttribute('color', new Float32BufferAttribute(colour, 3));
  };

  // The gizmo: the selected item (the target or a sphere) moved along an
  // axis or in a coordinate plane (TransformControls' arrows and squares).
  // Its centre handle is left out: a drag on the item itself is the core's
  // (space-input.js), in the plane facing the camera, as before.
  let gizmo = null;
  const handle = new Group();
  scene.add(handle);
  const attachGizmo = (element, { moved, turned, ended, yields }) => {
    // Registered before the gizmo's own listener, so it runs first: a press
    // on an item the core grabs (yields(event)) is not the gizmo's.
    const release = () => {
      if (gizmo) gizmo.enabled = true;
    };
    element.addEventListener('pointerdown', (e) => {
      if (gizmo) gizmo.enabled = !yields?.(e);
    });
    element.addEventListener('pointerup', release);
    element.addEventListener('pointercancel', release);
    gizmo = new TransformControls(camera, element);
    gizmo.setMode('translate');
    // Larger under a finger (its arrows' ends then about 44 px apart).
    gizmo.setSize(window.matchMedia?.('(pointer: coarse)').matches ? 1.5 : 0.9);
    gizmo.attach(handle);
    for (const part of [gizmo._gizmo.picker.translate, gizmo._gizmo.gizmo.translate]) {
      for (const c of [...part.children]) if (c.name === 'XYZ') c.removeFromParent();
    }
    scene.add(gizmo.getHelper());
    gizmo.addEventListener('change', () => renderer.render(scene, camera));
    gizmo.addEventListener('objectChange', () => {
      if (gizmo.mode === 'rotate') {
        // The handle's rotation, by rows (Matrix4's elements are by columns).
        const m = new Matrix4().makeRotationFromQuaternion(handle.quaternion).elements;
        turned?.([m[0], m[4], m[8], m[1], m[5], m[9], m[2], m[6], m[10]]);
      } else moved(handle.position.toArray());
    });
    gizmo.addEventListener('dragging-changed', (e) => {
      if (!e.value) ended();
    });
  };
  const placeGizmo = (v) => {
    if (!gizmo || gizmo.dragging) return;
    const k = v.selected === 'target' ? -1 : Number(v.selected.split(' ')[1]) - 1;
    const p = k < 0 ? v.target : v.spheres[k];
    if (p) handle.position.set(p[0], p[1], p[2]);
    // The pose task's target turns: the gizmo carries its orientation.
    const turnable = k < 0 && Boolean(v.target_rotation);
    if (turnable) handle.quaternion.setFromRotationMatrix(byRows(v.target_rotation));
    else handle.quaternion.identity();
    gizmo.setMode(turn && turnable ? 'rotate' : 'translate');
  };
  // Whether the gizmo turns the pose task's target (else it moves it).
  let turn = false;

  // The pose task's frames: the target's orientation and the hand's, each
  // as its x, y and z axes (red, green, blue).
  const targetFrame = new AxesHelper(0.12);
  const handFrame = new AxesHelper(0.08);
  targetFrame.visible = handFrame.visible = false;
  scene.add(targetFrame, handFrame);
  const placeFrame = (frame, rotation, at) => {
    frame.visible = Boolean(rotation);
    if (!rotation) return;
    frame.position.set(...at);
    frame.quaternion.setFromRotationMatrix(byRows(rotation));
  };

  // A robot's visuals (its URDF's <visual> meshes and shapes): a group a
  // link, placed each frame on the core's joint frame times the link's
  // frame in it (readRobot's links); the capsules are then drawn only when
  // "Collision volumes" is on.
  const robot = new Group();
  scene.add(robot);
  let placed = [];
  let volumes = true;
  const setRobot = ({ links, visuals, meshes }) => {
    const missing = new Set();
    let drawn = 0;
    placed = links.map((l) => {
      const g = new Group();
      g.name = `urdf link ${l.name}`;
      g.matrixAutoUpdate = false;
      const [r, t] = [l.rotation, l.translation];
      const local = new Matrix4().set(r[0][0], r[0][1], r[0][2], t[0], r[1][0], r[1][1], r[1][2], t[1], r[2][0], r[2][1], r[2][2], t[2], 0, 0, 0, 1);
      for (const v of visuals.filter((x) => x.link === l.name)) {
        const part = visualObject(v, meshes ?? {});
        if (!part) {
          if (v.geometry.mesh !== undefined) missing.add(v.geometry.mesh.split(/[\\/]/).pop());
          continue;
        }
        part.position.set(...v.xyz);
        part.rotation.copy(new Euler(v.rpy[0], v.rpy[1], v.rpy[2], 'ZYX'));
        part.traverse((o) => {
          if (o.isMesh) {
            o.castShadow = true;
            o.receiveShadow = true;
          }
        });
        g.add(part);
        drawn++;
      }
      robot.add(g);
      return { group: g, movedBy: l.moved_by, local };
    });
    volumes = drawn === 0;
    return { drawn, missing: [...missing] };
  };
  const joint = new Matrix4();
  const placeRobot = (frames) => {
    for (const p of placed) {
      if (p.movedBy === 0) joint.identity();
      else {
        const f = frames[p.movedBy - 1];
        joint.set(f[0], f[3], f[6], f[9], f[1], f[4], f[7], f[10], f[2], f[5], f[8], f[11], 0, 0, 0, 1);
      }
      p.group.matrix.multiplyMatrices(joint, p.local);
      p.group.matrixWorldNeedsUpdate = true;
    }
    arm.visible = volumes;
  };

  let size = { width: 1, height: 1 };
  const api = {
    renderer,
    /** Whether WebGL draws on the CPU here (no multisampling, plain shadows). */
    software,
    scene,
    camera,
    /** Sizes the drawing buffer: CSS px and the device-pixel ratio. */
    resize(width, height, dpr) {
      size = { width, height };
      renderer.setPixelRatio(Math.min(dpr, 2));
      renderer.setSize(width, height, false);
    },
    /**
     * Draws `v` (SpaceDemo.view()); `cells()` gives the slice atlas's
     * cells (SpaceDemo.layerView()) and is asked only when its revision
     * changed.
     */
    draw(v, cells) {
      camera.fov = (v.camera.fov * 180) / Math.PI;
      camera.aspect = size.width / size.height;
      camera.near = v.camera.near;
      camera.position.set(...v.camera.eye);
      camera.lookAt(...v.camera.focus);
      camera.updateProjectionMatrix();
      setFloor(v.floor);
      const r = v.radius;
      plate.position.set(v.base[0], v.base[1], 0.004);
      plate.scale.set(2 * r, 0.008, 2 * r);
      const l = links(v.links.length);
      const e = ends(2 * v.links.length);
      v.links.forEach(([a, b], i) => {
        l[i].name = `link ${i + 1}`;
        placeCylinder(l[i], a, b, r);
        e[2 * i].position.set(...a);
        e[2 * i + 1].position.set(...b);
        e[2 * i].scale.setScalar(r);
        e[2 * i + 1].scale.setScalar(r);
      });
      const j = joints(v.joints.length);
      v.joints.forEach((p, i) => {
        j[i].name = `joint ${i + 1}`;
        j[i].position.set(...p);
        // Just out of the capsule: a joint shows as a dark ball on the link.
        j[i].scale.setScalar(1.02 * r);
      });
      sphereMaterial.opacity = v.collision ? 0.6 : 0.3;
      const s = spheres(v.spheres.length);
      v.spheres.forEach(([x, y, z, rad], i) => {
        s[i].name = `sphere ${i + 1}`;
        s[i].position.set(x, y, z);
        s[i].scale.setScalar(rad);
      });
      setPoints(path, v.path, true);
      setPoints(trail, v.trail);
      setPoints(ghost, v.ghost ?? [], true);
      const g = ghostJoints(v.ghost ? v.ghost.length - 1 : 0);
      (v.ghost ?? []).slice(1).forEach((p, i) => {
        g[i].position.set(...p);
        g[i].scale.setScalar(0.25 * r);
      });
      placeGizmo(v);
      setSelfNear(v.self_near);
      placeFrame(targetFrame, v.target_rotation, v.target);
      placeFrame(handFrame, v.target_rotation && v.hand_rotation, v.hand);
      if (placed.length) placeRobot(v.frames);
      setEllipsoid('velocity', v.velocity, v.hand);
      setEllipsoid('force', v.force, v.hand);
      if (v.layer !== layerRevision) {
        layerRevision = v.layer;
        setLayer(cells());
      }
      renderer.render(scene, camera);
    },
    /**
     * The view with `overlay` (the 2-D canvas above it) drawn over it, as
     * one 2-D canvas of the drawing buffer's size: the PNG the page
     * saves, and what the tests read pixels from. Renders first, so the
     * WebGL buffer is read in the same task.
     */
    snapshot(overlay) {
      renderer.render(scene, camera);
      const out = document.createElement('canvas');
      out.width = canvas.width;
      out.height = canvas.height;
      const ctx = out.getContext('2d');
      ctx.drawImage(canvas, 0, 0);
      if (overlay) ctx.drawImage(overlay, 0, 0, out.width, out.height);
      return out;
    },
    /**
     * The gizmo on `element` (the overlay, which has the pointer): its
     * drags call `moved([x, y, z])` (the selected item's new centre) and,
     * at the end, `ended()`; a press where `yields(event)` is true is left
     * to the page.
     */
    attachGizmo,
    /**
     * A robot's visuals: `links` (readRobot's: name, moved_by, the frame in
     * the joint's), `visuals` (robot-open.js's visualsOf) and `meshes` ({
     * file name: bytes }: STL, OBJ, Collada). Returns { drawn, missing }:
     * how many visuals are drawn and the mesh files not at hand. With
     * visuals drawn the capsules are hidden until setVolumes(true).
     */
    setRobot,
    /** Whether the collision volumes (the capsules the planner uses) are drawn. */
    setVolumes(on) {
      volumes = on;
      arm.visible = on || !placed.length;
      renderer.render(scene, camera);
    },
    volumes: () => arm.visible,
    /**
     * Whether the gizmo turns the pose task's target (its rings) rather
     * than moving it (its arrows); takes effect at the next draw.
     */
    setTurn(on) {
      turn = on;
    },
    /** The gizmo's mode now: 'translate' or 'rotate'. */
    gizmoMode: () => gizmo?.mode ?? null,
    /** The gizmo's orientation as drawn, a rotation matrix by rows. */
    gizmoRotation: () => {
      const m = new Matrix4().makeRotationFromQuaternion(handle.quaternion).elements;
      return [m[0], m[4], m[8], m[1], m[5], m[9], m[2], m[6], m[10]];
    },
    /** The gizmo's item's centre as drawn, [x, y, z]. */
    gizmoAt: () => handle.position.toArray(),
    /** The gizmo's part under the pointer ('X', 'XY', ...) or null: a press there is the gizmo's. */
    gizmoAxis: () => (gizmo && gizmo.enabled ? gizmo.axis : null),
    dispose() {
      gizmo?.dispose();
      renderer.dispose();
    },
  };
  return api;
}
