// A robot of the user's in the page (robot-open.js): a URDF, with its
// meshes, chosen through "Open robot…" (files, a folder or a .zip) or
// fetched from `urdf=URL` is read by the workers' module,
// kept in this browser under its content hash and opened as `?robot=HASH`
// (a reload opens it again); the page says what the reader made of it; a
// qp run of it, saved as the run file, replays with `simulate --from`; a
// refused file leaves the page working with the reader's own message.
// Registered by e2e.mjs.

import assert from 'node:assert/strict';
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { test, open, clean, state, shots, textMatching, saidSoFar, heard } from './harness.mjs';
import { serve } from './serve.mjs';
import { cli, download, scratch } from './class-helpers.mjs';
// fflate as make web installs it for the page's own unzip (tools/package.json).
import { zipSync } from '../../tools/node_modules/fflate/esm/index.mjs';

/** Chooses `files` in "Open robot…" on `page` and waits for the robot's page. */
async function openRobot(page, files) {
  await page.click('#arm-panel summary');
  await Promise.all([page.waitForURL(/[?&]robot=[0-9a-f]{16}/, { timeout: 30000 }), page.setInputFiles('#robot-files', files)]);
  await page.waitForSelector('body[data-ready="true"]', { timeout: 30000 });
}

test('your robot: the UR5e from its URDF through Open robot…, what the reader made of it, a reload, and a qp run replayed by simulate --from', async () => {
  const page = await open('?task=1&method=numerical');
  const t0 = Date.now();
  await openRobot(page, 'robots/ur5e.urdf');
  // A measurement, not a test (the goal is 1 s to the first frame): from the file chosen to the robot's page ready.
  console.log(`measure: the UR5e's URDF chosen -> its page in space ready: ${Date.now() - t0} ms`);
  const s = await state(page);
  assert.deepEqual([s.kind, s.arm, s.arm_label, s.dof], ['space', 'robot', 'ur5e', 6]);
  assert.equal(s.spheres.length, 0, 'its own task has no sphere');
  const read = await page.textContent('#robot-read');
  assert.match(read, /ur5e: 6 moving joints from base_link to flange/);
  assert.match(read, /shoulder_pan \(revolute, -360° to 360°\)/);
  assert.match(read, /6 capsules/);
  assert.match(await page.textContent('#space-arm-source'), /your URDF ur5e\.urdf/);
  assert.equal(await page.inputValue('#arm-preset'), 'robot');
  // The 3-D view draws its six joints and its links.
  assert.equal(await page.evaluate(() => window.demo.controller.demo.view().joints.length), 8);
  // Kept in this browser: a reload opens it again, with the scene in the address.
  const hash = new URL(page.url()).searchParams.get('robot');
  await page.evaluate(() => window.demo.controller.demo.setSpheres(Float64Array.of(-0.6, 0, 0.2, 0.05)));
  await page.evaluate(() => window.demo.runUntil(0));
  await page.reload();
  await page.waitForSelector('body[data-ready="true"]', { timeout: 30000 });
  const again = await state(page);
  assert.equal(again.arm_label, 'ur5e');
  assert.equal(new URL(page.url()).searchParams.get('robot'), hash, 'the address names the same hash');
  // A qp run to its end, saved and replayed by the command line.
  await page.selectOption('#mode', 'qp');
  const end = await page.evaluate(() => window.demo.runUntil(1e9));
  assert.equal(end.failure, null);
  assert.ok(end.ended);
  const json = await download(page, '#save-run-json');
  const run = JSON.parse(json.text);
  assert.equal(run.method, 'qp');
  assert.equal(run.scene.arm.joints.length, 6, 'the file carries the chain read from the URDF');
  assert.equal(run.robot.name, 'ur5e', 'and the robot it came from, as simulate --urdf FILE --json records it');
  assert.match(run.robot.urdf, /<robot name="ur5e"/);
  const back = JSON.parse(cli(['simulate', '--from', json.path, '--json']));
  assert.equal(back.steps.length, run.steps.length);
  let worst = 0;
  back.steps.forEach((st, k) => st.theta.forEach((v, i) => (worst = Math.max(worst, Math.abs(v - run.steps[k].theta[i])))));
  assert.ok(worst < 1e-9, `simulate --from replays the page's run to ${worst} rad`);
  // Its figure names the robot as the command line does.
  const figure = await download(page, '#save-figure-svg');
  assert.match(figure.text, /ur5e \(6 joints, in space\), QP with dampers/);
  assert.match(cli(['simulate', '--from', json.path]), /^ur5e \(6 joints, in space\) \| method qp/);
  await page.locator('#stage').screenshot({ path: join(shots, 'robot-ur5e.png') });
  // From three sides, its volumes as the planner sees them.
  for (const [name, yaw, pitch] of [['front', 0, 0.2], ['side', Math.PI / 2, 0.25], ['above', 0.45, 1.2]]) {
    await page.evaluate(([yaw, pitch]) => window.demo.controller.demo.setView(yaw, pitch, window.demo.state().view[2]), [yaw, pitch]);
    await page.locator('#stage').screenshot({ path: join(shots, `robot-ur5e-${name}.png`) });
  }
  clean(page);
  await page.close();
});

test('your robot: the training panel trains its networks from its run file in two workers; Cases 1-3 then run on it', async () => {
  const page = await open('?task=1&method=numerical');
  await openRobot(page, 'robots/ur5e.urdf');
  await page.click('#train-panel summary');
  assert.match(await page.textContent('#train-panel summary'), /ur5e/);
  assert.match(await page.textContent('#train-panel p'), /redundant-ik train --urdf FILE/);
  assert.equal(await page.isVisible('#train-run'), true, 'the button is there for a robot of the user\'s');
  assert.equal(await page.locator('#mode option[value=case3]').isDisabled(), true, 'no networks before');
  // The benchmark times its own task from its run file: without networks, the exact methods only, and says so.
  await page.click('#bench-panel summary');
  // (The intro is written on the panel's toggle event, a task after the click.)
  await textMatching(page, '#bench-panel p', /^Times one Runge–Kutta step of the ur5e's own task .* redundant-ik bench --urdf FILE/);
  const bench = async () => {
    await page.click('#bench');
    await page.waitForFunction(() => /^(Per|The benchmark failed)/.test(document.getElementById('bench-result').textContent), null, { timeout: 120000 });
    return page.textContent('#bench-result');
  };
  assert.match(await bench(), /^Per RK4 step, .* takes .* here; Case 3 is not timed: this arm has no networks yet/);
  const files = await page.evaluate(() => window.demo.train({ samples: 300, epochs: 2 }).then((r) => [JSON.parse(r.phi), JSON.parse(r.v)]));
  // The weights files carry the chain read from the URDF (six joint frames), which the core checked before installing them.
  assert.deepEqual(files.map((f) => [f.format, f.arm.joints.length]), [['redundant-ik-weights/2', 6], ['redundant-ik-weights/2', 6]]);
  await textMatching(page, '#train-status', /Trained in .* Cases 1-3 now use them/);
  assert.equal((await state(page)).has_networks, true);
  await page.selectOption('#mode', 'case3');
  const end = await page.evaluate(() => window.demo.runUntil(1e9));
  assert.equal(end.method, 'case3');
  assert.ok(end.ended, 'a run of Case 3 with the networks just trained ends');
  assert.deepEqual(await download(page, '#train-download').then((d) => d.name), 'phi-ur5e-trained.json');
  // The run file carries the networks' files, so the command line replays the learned run on any machine.
  const json = await download(page, '#save-run-json');
  const run = JSON.parse(json.text);
  assert.deepEqual([run.method, typeof run.networks?.phi, typeof run.networks?.v], ['case3', 'string', 'string']);
  const back = JSON.parse(cli(['simulate', '--from', json.path, '--json']));
  let worst = 0;
  back.steps.forEach((st, k) => st.theta.forEach((v, i) => (worst = Math.max(worst, Math.abs(v - run.steps[k].theta[i])))));
  assert.equal(back.steps.length, run.steps.length);
  assert.ok(worst < 1e-9, `simulate --from replays the page's Case 3 run to ${worst} rad`);
  // The benchmark now times Case 3 with them.
  assert.match(await bench(), /^Per RK4 step, Case 3 .* is .* than .* Forward passes: Φ .*, v .*\.$/);
  assert.equal(await page.getAttribute('#bench-result', 'data-learned'), 'case3');
  // The slice atlas maps Case 3 with them in a worker.
  const a = await page.evaluate(() => window.demo.atlas({ methods: ['numerical', 'case3'], n: 3 }));
  assert.deepEqual(a.methods, ['numerical', 'case3']);
  clean(page);
  await page.close();
});

test('your robot: a URDF with an STL mesh (its volume fitted around the mesh), a mesh not chosen said as a warning', async () => {
  const page = await open('?arm=panda&method=numerical&autoplay=0');
  // Its tree has two leaves: the reader asks for the tip, which the page's field names.
  await page.click('#arm-panel summary');
  await page.setInputFiles('#robot-files', ['tests/data/urdf/slider_arm.urdf', 'tests/data/urdf/meshes/forearm.stl']);
  await page.waitForFunction(() => /name the tip link/.test(document.getElementById('message')?.textContent ?? ''), null, { timeout: 30000 });
  assert.match(await page.textContent('#message'), /the leaves 'camera', 'tool'.*Tip link/);
  await page.fill('#robot-tip', 'tool');
  await Promise.all([page.waitForURL(/[?&]robot=[0-9a-f]{16}/, { timeout: 30000 }), page.setInputFiles('#robot-files', ['tests/data/urdf/slider_arm.urdf', 'tests/data/urdf/meshes/forearm.stl'])]);
  await page.waitForSelector('body[data-ready="true"]', { timeout: 30000 });
  const s = await state(page);
  assert.equal(s.arm, 'robot');
  const read = await page.textContent('#robot-read');
  assert.match(read, /1 fitted around meshes/);
  assert.match(read, /Warning: .*missing\.stl/);
  assert.match(read, /prismatic/);
  clean(page);
  await page.close();
});

test("your robot: its URDF's visuals drawn on the core's frames (three's matrices against Pinocchio's link frames to 1e-6), the collision volumes on a switch", async () => {
  // The test arm with visuals: its forearm's STL mesh in orange, a box on the upper arm, an OBJ and a Collada mesh.
  const text = readFileSync('tests/data/urdf/slider_arm.urdf', 'utf8')
    .replace('<link name="forearm">', '<link name="forearm"><visual><origin xyz="0.15 0 0"/><geometry><mesh filename="package://slider_arm/meshes/forearm.stl"/></geometry><material name="orange"><color rgba="1 0.5 0 1"/></material></visual>')
    .replace('<link name="upper_arm">', '<link name="upper_arm"><visual><origin xyz="0.2 0 0" rpy="0 1.5707963267948966 0"/><geometry><box size="0.08 0.08 0.4"/></geometry></visual><visual><geometry><mesh filename="package://slider_arm/meshes/shoulder.dae"/></geometry></visual>')
    // The two other mesh formats three's loaders read: a Collada triangle on the forearm, an OBJ tetrahedron on the hand.
    .replace('<link name="hand">', '<link name="hand"><visual><geometry><mesh filename="package://slider_arm/meshes/wrist.obj"/></geometry></visual>')
    .replace('<link name="forearm">', '<link name="forearm"><visual><geometry><mesh filename="package://slider_arm/meshes/elbow.dae" scale="2 2 2"/></geometry></visual>');
  const path = join(scratch, 'visual_arm.urdf');
  writeFileSync(path, text);
  const obj = join(scratch, 'wrist.obj');
  writeFileSync(obj, 'v 0 0 0\nv 0.05 0 0\nv 0 0.05 0\nv 0 0 0.05\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n');
  const dae = join(scratch, 'elbow.dae');
  writeFileSync(
    dae,
    `<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="meter" meter="1"/><up_axis>Z_UP</up_axis></asset>
  <library_geometries><geometry id="tri"><mesh>
    <source id="pos"><float_array id="pos-array" count="9">0 0 0 0.05 0 0 0 0.05 0</float_array>
      <technique_common><accessor source="#pos-array" count="3" stride="3"><param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>
    <vertices id="vtx"><input semantic="POSITION" source="#pos"/></vertices>
    <triangles count="1"><input semantic="VERTEX" source="#vtx" offset="0"/><p>0 1 2</p></triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="scene"><node id="n"><instance_geometry url="#tri"/></node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
`,
  );
  const page = await open('?arm=panda&method=numerical&autoplay=0');
  await page.click('#arm-panel summary');
  await page.fill('#robot-tip', 'tool');
  await Promise.all([page.waitForURL(/[?&]robot=[0-9a-f]{16}/, { timeout: 30000 }), page.setInputFiles('#robot-files', [path, 'tests/data/urdf/meshes/forearm.stl', obj, dae])]);
  await page.waitForSelector('body[data-ready="true"]', { timeout: 30000 });
  assert.match(await page.textContent('#robot-read'), /Drawn: 4 visuals from the URDF; mesh files not chosen, so not drawn: shoulder\.dae/);
  // Each format's loader made its mesh: the OBJ's four faces (12 corners), the Collada triangle scaled by the URDF's 2.
  const meshes = await page.evaluate(() => {
    const scene = window.demo.controller.view3d.three.scene;
    const corners = (link) => {
      let n = 0;
      scene.getObjectByName(`urdf link ${link}`).traverse((o) => o.isMesh && (n += o.geometry.attributes.position.count));
      return n;
    };
    scene.updateMatrixWorld(true);
    let scaled = null;
    scene.getObjectByName('urdf link forearm').traverse((o) => {
      if (o.isMesh && o.geometry.attributes.position.count === 3) scaled = o.getWorldScale(o.position.clone()).toArray();
    });
    return { hand: corners('hand'), scaled };
  });
  assert.equal(meshes.hand, 12, 'the OBJ tetrahedron');
  assert.ok(meshes.scaled && meshes.scaled.every((v) => Math.abs(v - 2) < 1e-9), `the Collada triangle, scaled by 2: ${meshes.scaled}`);
  // At Pinocchio's poses of this arm, each moving joint's child link is drawn where Pinocchio has its frame.
  const pinocchio = JSON.parse(readFileSync('tests/data/urdf/pinocchio.json', 'utf8')).files.find((f) => f.file.endsWith('slider_arm.urdf'));
  const children = ['carriage', 'upper_arm', 'forearm', 'hand'];
  let worst = 0;
  for (const run of pinocchio.runs.slice(0, 3)) {
    const drawn = await page.evaluate(async ([q, names]) => {
      const c = window.demo.controller;
      c.demo.setStart(Float64Array.from(q));
      c.view3d.draw();
      const scene = c.view3d.three.scene;
      scene.updateMatrixWorld(true);
      return names.map((n) => scene.getObjectByName(`urdf link ${n}`).matrixWorld.elements);
    }, [run.q, children]);
    drawn.forEach((e, k) => {
      const { rotation: R, translation: t } = run.joints[k];
      for (let r = 0; r < 3; r++) {
        worst = Math.max(worst, Math.abs(e[12 + r] - t[r]));
        for (let col = 0; col < 3; col++) worst = Math.max(worst, Math.abs(e[4 * col + r] - R[r][col]));
      }
    });
  }
  assert.ok(worst < 1e-6, `the links are drawn on Pinocchio's frames to ${worst}`);
  // The visuals hide the capsules; "Collision volumes" shows them over the meshes.
  const volumes = () => page.evaluate(() => window.demo.controller.view3d.three.volumes());
  assert.equal(await volumes(), false);
  await page.locator('#stage').screenshot({ path: join(shots, 'robot-visuals.png') });
  const said = await saidSoFar(page);
  await page.click('#show-volumes');
  assert.equal(await volumes(), true);
  assert.equal(await page.getAttribute('#show-volumes', 'aria-pressed'), 'true');
  await heard(page, /collision volumes shown/, said);
  await page.locator('#stage').screenshot({ path: join(shots, 'robot-volumes.png') });
  clean(page);
  await page.close();
});

test('your robot: the same arm as a .zip, as a folder (a ROS package, its package.xml left out), and from urdf=URL on a host that allows it, or the CORS message', async () => {
  const urdf = readFileSync('tests/data/urdf/slider_arm.urdf');
  const stl = readFileSync('tests/data/urdf/meshes/forearm.stl');
  const packageXml = Buffer.from('<?xml version="1.0"?><package format="2"><name>slider_arm</name></package>');
  // A .zip of the package: its URDF under urdf/, its mesh under meshes/.
  const zip = join(scratch, 'slider_arm.zip');
  writeFileSync(zip, zipSync({ 'slider_arm/package.xml': packageXml, 'slider_arm/urdf/slider_arm.urdf': urdf, 'slider_arm/meshes/forearm.stl': stl }));
  const page = await open('?arm=panda&method=numerical&autoplay=0');
  await page.click('#arm-panel summary');
  await page.fill('#robot-tip', 'tool');
  await Promise.all([page.waitForURL(/[?&]robot=[0-9a-f]{16}/, { timeout: 30000 }), page.setInputFiles('#robot-files', zip)]);
  await page.waitForSelector('body[data-ready="true"]', { timeout: 30000 });
  const zipped = new URL(page.url()).searchParams.get('robot');
  assert.match(await page.textContent('#robot-read'), /1 fitted around meshes/, 'the mesh inside the archive gave its volume');
  // The same files as a folder: the same robot, the same hash.
  const folder = join(scratch, 'slider_arm');
  mkdirSync(join(folder, 'urdf'), { recursive: true });
  mkdirSync(join(folder, 'meshes'), { recursive: true });
  writeFileSync(join(folder, 'package.xml'), packageXml);
  writeFileSync(join(folder, 'urdf/slider_arm.urdf'), urdf);
  writeFileSync(join(folder, 'meshes/forearm.stl'), stl);
  await page.click('#arm-panel summary');
  await page.fill('#robot-tip', 'tool');
  await Promise.all([page.waitForURL(/[?&]robot=[0-9a-f]{16}/, { timeout: 30000 }), page.setInputFiles('#robot-folder', folder)]);
  await page.waitForSelector('body[data-ready="true"]', { timeout: 30000 });
  assert.equal(new URL(page.url()).searchParams.get('robot'), zipped, 'the folder is the same robot as the archive');
  clean(page);
  await page.close();
  // urdf=URL: the package on a host of its own (another origin), which sends
  // Access-Control-Allow-Origin or not; its mesh is beside the URDF's folder (package://).
  const root = join(scratch, 'host');
  mkdirSync(join(root, 'slider_arm/urdf'), { recursive: true });
  mkdirSync(join(root, 'slider_arm/meshes'), { recursive: true });
  writeFileSync(join(root, 'slider_arm/urdf/slider_arm.urdf'), urdf);
  writeFileSync(join(root, 'slider_arm/meshes/forearm.stl'), stl);
  const [open_, closed] = await Promise.all([serve(root, ['--cors']), serve(root)]);
  try {
    const url = `${open_.url}slider_arm/urdf/slider_arm.urdf`;
    const allowed = await open(`?urdf=${encodeURIComponent(url)}&tip=tool&method=qp`);
    const s = await state(allowed);
    assert.deepEqual([s.arm, s.arm_label, s.method], ['robot', 'slider_arm', 'qp']);
    assert.match(await allowed.textContent('#robot-read'), /1 fitted around meshes/, 'the mesh was fetched beside the URDF');
    const link = new URL(allowed.url()).searchParams;
    assert.deepEqual([link.get('urdf'), link.get('tip'), link.has('robot')], [url, 'tool', false], 'the link names the URDF, so any browser fetches it again');
    // The one mesh the host has not (meshes/missing.stl) is the one failed request the browser logs.
    assert.deepEqual(allowed.problems, ['console error: Failed to load resource: the server responded with a status of 404 (File not found)']);
    allowed.problems.length = 0;
    clean(allowed);
    await allowed.close();
    const blocked = `${closed.url}slider_arm/urdf/slider_arm.urdf`;
    const refused = await open(`?urdf=${encodeURIComponent(blocked)}&tip=tool`);
    assert.equal((await state(refused)).arm, 'panda', 'the first shipped arm instead');
    assert.match(await refused.textContent('#message'), /urdf: http:\/\/127\.0\.0\.1:\d+\/slider_arm\/urdf\/slider_arm\.urdf could not be fetched: .*CORS/);
    await refused.close();
  } finally {
    open_.stop();
    closed.stop();
  }
});

test('your robot: hostile and wrong files are refused with the reader\'s own message, and the page goes on', async () => {
  const page = await open('?arm=panda&method=qp&autoplay=0');
  await page.click('#arm-panel summary');
  const bad = [
    ['entity.urdf', '<?xml version="1.0"?><!DOCTYPE r [<!ENTITY a "aaaaaaaaaa">]><robot name="r">&a;</robot>', /DTD|document type|entit/i],
    ['broken.urdf', '<robot name="r"><link name="a"></robot>', /robot could not be opened/],
    ['floating.urdf', '<robot name="r"><link name="a"/><link name="b"/><joint name="j" type="floating"><parent link="a"/><child link="b"/></joint></robot>', /floating/],
    ['notes.txt', 'hello', /no \.urdf file was chosen/],
  ];
  for (const [name, text, why] of bad) {
    const path = join(scratch, name);
    writeFileSync(path, text);
    await page.setInputFiles('#robot-files', path);
    await page.waitForFunction(() => /could not be opened/.test(document.getElementById('message')?.textContent ?? ''), null, { timeout: 30000 });
    const message = await page.textContent('#message');
    assert.match(message, why, `${name}: ${message}`);
    assert.doesNotMatch(page.url(), /robot=/, `${name} opened nothing`);
    await page.evaluate(() => (document.getElementById('message').textContent = ''));
  }
  // Two URDFs at once are refused by name.
  await page.setInputFiles('#robot-files', ['robots/ur5e.urdf', 'robots/panda.urdf']);
  await page.waitForFunction(() => /2 URDF files/.test(document.getElementById('message')?.textContent ?? ''), null, { timeout: 30000 });
  // The page still runs its Panda.
  const s = await page.evaluate(() => window.demo.runUntil(1e9));
  assert.equal(s.arm, 'panda');
  assert.ok(s.ended);
  clean(page);
  await page.close();
});

test('your robot: an address naming a robot this browser has not kept, or a hostile one, opens the first shipped arm and says why', async () => {
  const cases = [
    ['robot=0123456789abcdef', /robot: the robot 0123456789abcdef is not in this browser's storage/],
    ['robot=%3Cscript%3Ealert(1)%3C%2Fscript%3E', /robot: '<script>alert\(1\)<\/script>' is not a robot's hash \(16 hexadecimal digits/],
    ['urdf=javascript:alert(1)', /urdf: javascript:alert\(1\) could not be fetched/],
    ['urdf=%00%FF', /urdf: .* could not be fetched|urdf: Invalid URL|urdf: .*HTTP 404/],
  ];
  for (const [query, why] of cases) {
    const page = await open(`?${query}&method=qp`);
    const s = await state(page);
    assert.equal(s.arm, 'panda', query);
    assert.match(await page.textContent('#message'), why, query);
    assert.equal(await page.evaluate(() => document.body.innerHTML.includes('<script>alert')), false, 'nothing of the address became markup');
    const end = await page.evaluate(() => window.demo.runUntil(1e9));
    assert.ok(end.ended, `${query}: the Panda runs`);
    page.problems.length = 0; // a failed fetch is logged by the browser
    await page.close();
  }
});
