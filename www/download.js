// Files the page hands the user: text and blobs saved through a link's
// download attribute, an SVG turned into a PNG through a canvas, and the
// name a file of the current scene gets.

/** Saves `blob` as a file called `name`. */
export function saveBlob(name, blob) {
  const a = document.createElement('a');
  a.href = URL.createObjectURL(blob);
  a.download = name;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 2000);
}

/** Saves `text` as a file called `name` of MIME type `type`. */
export function saveText(name, text, type = 'text/plain') {
  saveBlob(name, new Blob([text], { type }));
}

/** The pixel size an SVG declares: `[width, height]`. */
export function svgSize(svg) {
  const m = /<svg[^>]*\bwidth="(\d+)"[^>]*\bheight="(\d+)"/.exec(svg);
  if (!m) throw new Error('the figure declares no size');
  return [Number(m[1]), Number(m[2])];
}

/** An SVG drawn on a white canvas `scale` times its size: a PNG blob. */
export async function svgToPng(svg, scale = 2) {
  const [w, h] = svgSize(svg);
  const url = URL.createObjectURL(new Blob([svg], { type: 'image/svg+xml' }));
  try {
    const img = new Image();
    img.src = url;
    await img.decode();
    const canvas = document.createElement('canvas');
    canvas.width = w * scale;
    canvas.height = h * scale;
    const ctx = canvas.getContext('2d');
    ctx.fillStyle = '#fff';
    ctx.fillRect(0, 0, canvas.width, canvas.height);
    ctx.drawImage(img, 0, 0, canvas.width, canvas.height);
    return await new Promise((resolve, reject) =>
      canvas.toBlob((b) => (b ? resolve(b) : reject(new Error('the browser could not make a PNG'))), 'image/png'),
    );
  } finally {
    URL.revokeObjectURL(url);
  }
}

/** A file name's stem for the scene in `state`: `task1-case3` (the arm where it is not the paper's). */
export function stem(state) {
  const arm = state.paper_arm ? '' : `-arm${state.arm_text.replace(/[:,]/g, '_')}`;
  return `task${state.task}-${state.method}${arm}`;
}

/** Rows as CSV: a header and one line per row; cells with a comma or a quote are quoted. */
export function csv(header, rows) {
  const cell = (v) => {
    const s = v === null || v === undefined ? '' : String(v);
    return /[",\n]/.test(s) ? `"${s.replace(/"/g, '""')}"` : s;
  };
  return [header, ...rows].map((r) => r.map(cell).join(',')).join('\n') + '\n';
}
