// The builds that carry the page's files inline, and the npm package,
// bundled by esbuild (pinned in tools/package-lock.json) from www/ as
// `make web` leaves it. Run by scripts/bundle.sh:
//
//   node tools/bundle.mjs offline   # dist/redundant-ik.html: the page in one file
//   node tools/bundle.mjs npm       # target/npm/redundant-ik/: the package folder
//   node tools/bundle.mjs view      # www/pkg/three-view.js (three.js) and www/pkg/unzip.js (fflate)
//
// The files a build inlines (the SIMD builds of both modules, the built-in
// networks' weights files of every shipped set, bench-native.json and the
// workers' script bundled with its glue) are gzipped, in base64, and
// become data: URLs in the browser (www/inline-assets.js) that module.js's
// assetUrl() answers with.

import * as esbuild from 'esbuild';
import { copyFileSync, existsSync, mkdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { dirname, join, relative } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { gzipSync } from 'node:zlib';

const root = join(dirname(fileURLToPath(import.meta.url)), '..');
const www = join(root, 'www');

function fail(message) {
  console.error(`bundle: ${message}`);
  process.exit(1);
}

function read(path) {
  try {
    return readFileSync(path);
  } catch (e) {
    fail(`cannot read ${relative(root, path)} (${e.code}); run 'make web' first`);
  }
}

/** A string of Cargo.toml's [package] table (version, description, repository), or undefined. */
function cargo(key) {
  const toml = read(join(root, 'Cargo.toml')).toString();
  const pkg = toml.slice(toml.indexOf('[package]')).split(/\n\[/)[0];
  return pkg.match(new RegExp(`^${key}\\s*=\\s*"([^"]+)"`, 'm'))?.[1];
}

function version() {
  return cargo('version') ?? fail("Cargo.toml's [package] has no version");
}

/** The weights files of every shipped network set, the planar arms' and the arms in space's, as the page's module names them. */
async function weightsFiles() {
  const glue = await import(pathToFileURL(join(www, 'pkg/redundant_ik.js')).href);
  glue.initSync({ module: read(join(www, 'pkg/redundant_ik_simd_bg.wasm')) });
  const planar = glue.networkSets().flatMap((set) => glue.builtinWeightsFiles(set));
  const space = glue.spaceNetworkSets().flatMap((set) => set.files);
  return [...new Set([...planar, ...space])];
}

const BANNER = `// redundant-ik ${version()} (MIT OR Apache-2.0), bundled by tools/bundle.mjs from www/.`;
const COMMON = { bundle: true, format: 'esm', target: 'es2022', minify: true, legalComments: 'none', write: false, logLevel: 'error', banner: { js: BANNER } };

/** Bundles `contents` (a module in www/) into one module's text; `inputs` collects the files read. */
async function bundle(contents, inputs = new Set()) {
  const assets = {
    name: 'inline-assets',
    setup(b) {
      b.onResolve({ filter: /^redundant-ik:assets$/ }, (a) => ({ path: a.path, namespace: 'assets' }));
      b.onLoad({ filter: /.*/, namespace: 'assets' }, async () => ({ contents: `export default ${JSON.stringify(await inlineFiles())};`, loader: 'js' }));
    },
  };
  const out = await esbuild.build({ ...COMMON, stdin: { contents, resolveDir: www, sourcefile: 'entry.js' }, metafile: true, plugins: [assets] });
  // The files read, not the entry itself nor the inline files.
  for (const input of Object.keys(out.metafile.inputs)) if (existsSync(join(root, input))) inputs.add(relative(www, join(root, input)));
  return out.outputFiles[0].text;
}

let inlined = null;
/** `{ path: { type, gzip } }`: every file an inline build carries, by its path under www/. */
function inlineFiles() {
  inlined ??= (async () => {
    const files = {};
    const add = (path, type, bytes) => (files[path] = { type, gzip: gzipSync(bytes, { level: 9 }).toString('base64') });
    add('pkg/redundant_ik_simd_bg.wasm', 'application/wasm', read(join(www, 'pkg/redundant_ik_simd_bg.wasm')));
    add('pkg/redundant_ik_worker_simd_bg.wasm', 'application/wasm', read(join(www, 'pkg/redundant_ik_worker_simd_bg.wasm')));
    for (const name of await weightsFiles()) add(`weights/${name}`, 'application/json', read(join(www, 'weights', name)));
    add('bench-native.json', 'application/json', read(join(www, 'bench-native.json')));
    add('worker.js', 'text/javascript', Buffer.from(await bundle("import './worker.js';")));
    return files;
  })();
  return inlined;
}

/** An inline build's entry: the files installed, then `module` (in www/) run; `exports` re-exported. */
const inlineEntry = (module, exports = '') =>
  `import { installAssets } from './inline-assets.js';\nimport files from 'redundant-ik:assets';\nawait installAssets(files);\n${exports ? `const m = await import('${module}');\n${exports}` : `await import('${module}');`}\n`;

/** Text inlined in a <script> or <style> must not close it early. */
function inlinable(text, tag) {
  if (new RegExp(`</${tag}`, 'i').test(text)) fail(`the inlined ${tag} contains '</${tag}'`);
  return text;
}

/** dist/redundant-ik.html: index.html with its styles and its one module inline. */
async function offline() {
  let html = read(join(www, 'index.html')).toString();
  // The page's check for file:// (no module runs there) is not for this
  // file, whose module is inline and runs from file://.
  const check = /\s*<!--(?:(?!-->)[^])*-->\s*<script data-file-check>(?:(?!<\/script>)[^])*<\/script>/;
  if (!check.test(html)) fail('index.html has no <script data-file-check> to leave out');
  html = html.replace(check, '');
  html = html.replace(/<link rel="stylesheet" href="([^"]+)">/g, (_, href) => `<style>\n${inlinable(read(join(www, href)).toString(), 'style')}</style>`);
  const scripts = [...html.matchAll(/<script type="module" src="([^"]+)"><\/script>/g)];
  if (scripts.length !== 1) fail(`index.html has ${scripts.length} module scripts, expected one`);
  const js = await bundle(inlineEntry(`./${scripts[0][1]}`));
  html = html.replace(scripts[0][0], () => `<script type="module">\n${inlinable(js, 'script')}</script>`);
  if (/<(script|link)[^>]+(src|href)="(?!data:|https?:|#)[^"]+\.(js|css)"/.test(html)) fail('index.html still loads a file beside it');
  const out = join(root, 'dist/redundant-ik.html');
  mkdirSync(dirname(out), { recursive: true });
  writeFileSync(out, html);
  console.log(`bundle: ${relative(root, out)}: ${Buffer.byteLength(html).toLocaleString("en")} B`);
}

/** The package's README: what it exports and where the recipes are. */
function readme(v) {
  return `# redundant-ik ${v}

The browser demo of the redundant-ik crate (motion planning for redundant arms, planar and in space, after *An
ANN Approach for the Motion Planning of Redundant Manipulators*) as a custom element, its WebAssembly module, a build with every file inline, and
an anywidget module for notebooks. No runtime dependencies.

\`\`\`html
<script type="module">import 'redundant-ik';</script>
<redundant-ik-demo task="1" method="numerical"></redundant-ik-demo>
\`\`\`

| entry | what |
|---|---|
| \`redundant-ik\`, \`redundant-ik/element\` | the \`<redundant-ik-demo>\` element; loads the .wasm and weights files beside it (serve them as \`application/wasm\` and JSON) |
| \`redundant-ik/module\` | the page's module API (\`loadModule\`, \`methods\`, \`limits\`, \`Demo\`, \`assetUrl\`, ...) |
| \`redundant-ik/compat\` | the element with every .wasm and weights file inline: nothing fetched (its module is widget.js) |
| \`redundant-ik/widget\` | an anywidget front-end module (\`export default { render }\`), one self-contained file |

Attributes (and the widget's traits): \`task\`, \`method\`, \`lambda\`, \`feedback\`, \`weighting\`,
\`floor\`, \`path\`, \`autoplay\`, \`plots\`, with the page's address keys; an arm in space with
\`arm="panda"\` or a robot's \`urdf\` (with \`base\`, \`tip\`). Recipes for plain HTML,
mdBook, Jupyter Book, Quarto, Docusaurus and notebooks: docs/embedding.md in the repository.

Licence: MIT OR Apache-2.0 (LICENSE-MIT, LICENSE-APACHE).
`;
}

/** target/npm/redundant-ik/: the element's files as www/ has them, the inline builds, package.json. */
async function npm() {
  const v = version();
  const out = join(root, 'target/npm/redundant-ik');
  rmSync(out, { recursive: true, force: true });
  mkdirSync(out, { recursive: true });
  const save = (path, text) => {
    mkdirSync(dirname(join(out, path)), { recursive: true });
    writeFileSync(join(out, path), text);
  };
  // The modules the element, the page's module and the workers read (their import graphs).
  const modules = new Set();
  await bundle("import './redundant-ik-demo.js'; import './module.js'; import './worker.js'; import './widget.js';", modules);
  const files = [...modules, 'pkg/redundant_ik_bg.wasm', 'pkg/redundant_ik_simd_bg.wasm', 'pkg/redundant_ik_worker_bg.wasm', 'pkg/redundant_ik_worker_simd_bg.wasm', 'bench-native.json', ...(await weightsFiles()).map((n) => `weights/${n}`)];
  for (const f of files) {
    mkdirSync(dirname(join(out, f)), { recursive: true });
    copyFileSync(join(www, f), join(out, f));
  }
  // One self-contained bundle, the widget (anywidget loads one module's
  // text), which defines the element; compat.js is that module too.
  save('widget.js', await bundle(inlineEntry('./widget.js', 'export default m.default;')));
  save('compat.js', `${BANNER}\n// The element with every file inline (widget.js defines it; its default export is the notebook widget).\nexport { default } from './widget.js';\n`);
  for (const f of ['LICENSE-MIT', 'LICENSE-APACHE']) copyFileSync(join(root, f), join(out, f));
  save('README.md', readme(v));
  const pkg = {
    name: 'redundant-ik',
    version: v,
    description: `${cargo('description')} The browser demo as a custom element, its WebAssembly module and an anywidget module.`,
    type: 'module',
    exports: {
      '.': './redundant-ik-demo.js',
      './element': './redundant-ik-demo.js',
      './module': './module.js',
      './compat': './compat.js',
      './widget': './widget.js',
      './package.json': './package.json',
    },
    files: [...new Set([...files.map((f) => f.split('/')[0]), 'compat.js', 'widget.js'])].sort(),
    sideEffects: ['./redundant-ik-demo.js', './compat.js', './widget.js'],
    license: 'MIT OR Apache-2.0',
    // Cargo.toml's repository, where it names one.
    ...(cargo('repository') ? { repository: { type: 'git', url: `git+${cargo('repository')}` } } : {}),
    keywords: ['robotics', 'inverse-kinematics', 'redundant-manipulator', 'webassembly', 'custom-element', 'web-component', 'anywidget', 'simulation'],
  };
  save('package.json', `${JSON.stringify(pkg, null, 2)}\n`);
  if (!pkg.repository) console.log("bundle: Cargo.toml names no repository, so package.json has none");
  for (const f of ['compat.js', 'widget.js']) console.log(`bundle: ${relative(root, join(out, f))}: ${readFileSync(join(out, f)).length.toLocaleString('en')} B`);
}

/**
 * The page's vendored modules, each one file under www/pkg/ (make web runs
 * this): three-view.js, the 3-D view of the arms in space (www/view/) with
 * the parts of three.js it imports (space-view.js imports it only when an
 * arm in space is shown), and unzip.js, fflate's unzip for a robot's .zip
 * (robot-open.js imports it only then). three and fflate are pinned in
 * tools/package-lock.json.
 */
async function view() {
  const pinned = (name) => JSON.parse(read(join(root, `tools/node_modules/${name}/package.json`))).version;
  const modules = [
    ['view/three-view.js', 'pkg/three-view.js', `the 3-D view (MIT OR Apache-2.0) with three.js ${pinned('three')} (MIT, Copyright 2010-2025 three.js authors)`],
    ['view/unzip.js', 'pkg/unzip.js', `a robot's .zip unpacked with fflate ${pinned('fflate')} (MIT, Copyright 2023 Arjun Barrett)`],
  ];
  for (const [entry, file, what] of modules) {
    const out = join(www, file);
    await esbuild.build({
      ...COMMON,
      entryPoints: [join(www, entry)],
      nodePaths: [join(root, 'tools/node_modules')],
      banner: { js: `// redundant-ik ${version()}: ${what}, bundled by tools/bundle.mjs.` },
      write: true,
      outfile: out,
    });
    const bytes = readFileSync(out);
    console.log(`bundle: ${relative(root, out)}: ${bytes.length.toLocaleString('en')} B, gzip -9 ${gzipSync(bytes, { level: 9 }).length.toLocaleString('en')} B`);
  }
}

const what = process.argv[2];
if (what === 'offline') await offline();
else if (what === 'npm') await npm();
else if (what === 'view') await view();
else fail(`usage: node tools/bundle.mjs offline|npm|view (got '${what ?? ''}')`);
