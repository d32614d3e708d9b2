// The helpers of the class tests (class.mjs, class-panels.mjs): the
// command-line tool, downloads, PNG sizes, SVG parsing, closeness.

import { readFileSync, writeFileSync, mkdtempSync } from 'node:fs';
import { spawnSync } from 'node:child_process';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import assert from 'node:assert/strict';

export const CLI = process.env.REDUNDANT_IK ?? 'target/debug/redundant-ik';
export const scratch = mkdtempSync(join(tmpdir(), 'redundant-ik-class-'));

/** Runs the command-line tool; its standard output. */
export function cli(args) {
  const out = spawnSync(CLI, args, { encoding: 'utf8', maxBuffer: 64 << 20 });
  assert.equal(out.status, 0, `${args.join(' ')}: ${out.stderr}`);
  return out.stdout;
}

/** Clicks `selector` and returns the file it downloads: `{ name, bytes, text }`. */
export async function download(page, selector) {
  const [d] = await Promise.all([page.waitForEvent('download', { timeout: 60000 }), page.click(selector)]);
  const bytes = readFileSync(await d.path());
  const name = d.suggestedFilename();
  writeFileSync(join(scratch, name), bytes);
  return { name, bytes, text: bytes.toString('utf8'), path: join(scratch, name) };
}

/** Width and height of a PNG, from its IHDR chunk. */
export function pngSize(bytes) {
  assert.deepEqual([...bytes.subarray(1, 4)], [0x50, 0x4e, 0x47], 'a PNG signature');
  return [bytes.readUInt32BE(16), bytes.readUInt32BE(20)];
}

/** The SVG parsed by the browser: its size and its polylines' points, or a parse error. */
export function parseSvg(page, text) {
  return page.evaluate((svg) => {
    const doc = new DOMParser().parseFromString(svg, 'image/svg+xml');
    const error = doc.querySelector('parsererror');
    const root = doc.documentElement;
    return {
      error: error ? error.textContent : null,
      size: [Number(root.getAttribute('width')), Number(root.getAttribute('height'))],
      polylines: [...doc.querySelectorAll('polyline')].map((p) => ({
        stroke: p.getAttribute('stroke'),
        width: p.getAttribute('stroke-width'),
        points: p.getAttribute('points').trim().split(/\s+/).map((xy) => xy.split(',').map(Number)),
      })),
      texts: [...doc.querySelectorAll('text')].map((t) => t.textContent.trim()),
    };
  }, text);
}

export const close = (a, b, tol, what) => assert.ok(Math.abs(a - b) <= tol, `${what}: ${a} vs ${b}`);
