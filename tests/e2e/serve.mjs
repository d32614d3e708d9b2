// scripts/serve.py started from a script (the embed test's course pages,
// the package test's scratch folder, scripts/wire-bytes.mjs): on a free
// 127.0.0.1 port, its address read from the first line it prints.

import { spawn } from 'node:child_process';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const SERVE = join(dirname(fileURLToPath(import.meta.url)), '../../scripts/serve.py');

/**
 * Serves `dir` (`args`: more of serve.py's options, e.g. `['--cors']`).
 * Resolves to `{ url, stop }` once the server prints its address; rejects
 * with what it printed if it exits first.
 */
export function serve(dir, args = []) {
  return new Promise((resolve, reject) => {
    const server = spawn('python3', [SERVE, '--port', '0', '--dir', dir, '--quiet', ...args]);
    let out = '';
    server.stdout.on('data', (d) => {
      out += d;
      const m = out.match(/http:\/\/127\.0\.0\.1:\d+\/\S*/);
      if (m) resolve({ url: m[0], stop: () => server.kill() });
    });
    server.stderr.on('data', (d) => (out += d));
    server.on('exit', (code) => reject(new Error(`scripts/serve.py exited (${code}): ${out}`)));
  });
}
