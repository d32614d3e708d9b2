// How the page writes numbers: one place for the readouts, the tables, the
// tips and the reports.

/** A number with `digits` decimals, or '–' where there is none. */
export function fixed(v, digits = 3) {
  if (v === null || v === undefined || !Number.isFinite(v)) return '–';
  return v.toFixed(digits);
}

/**
 * A coordinate as an address, a snippet or a file name writes it: with the
 * fewest decimals, three to nine, that give the number up to floating-point
 * noise (1e-12 m: an atlas cell's 1.5299999999999998 is 1.530, its
 * 0.30750000000000005 is 0.3075), else in full (a dragged one), so the
 * scene it reproduces is the one on screen.
 */
export function coordinate(v) {
  for (let d = 3; d <= 9; d++) {
    const t = v.toFixed(d);
    if (Math.abs(Number(t) - v) <= 1e-12) return t;
  }
  return String(v);
}

/** A length that may be tiny (a tracking error), with its unit. */
export function metres(v) {
  if (v === null || v === undefined || !Number.isFinite(v)) return '–';
  if (v >= 0.01) return `${v.toFixed(3)} m`;
  if (v >= 1e-5) return `${(v * 1000).toFixed(2)} mm`;
  return '< 0.01 mm';
}

/** A number in scientific notation with three figures, or '–'. */
export const sci = (v) => (Number.isFinite(v) ? v.toExponential(2) : '–');

/** Seconds as "12.3 s" or "2 min 5 s". */
export const seconds = (s) => (s >= 60 ? `${Math.floor(s / 60)} min ${Math.round(s % 60)} s` : `${s.toFixed(1)} s`);

/** Nanoseconds as "850 ns" or "2.25 µs", or '–'. */
export const nanoseconds = (ns) =>
  Number.isFinite(ns) ? (ns >= 1000 ? `${(ns / 1000).toFixed(2)} µs` : `${ns.toFixed(0)} ns`) : '–';

/** A rate as a percentage with one decimal, or '–'. */
export const percent = (rate) => (rate === null || rate === undefined ? '–' : `${(100 * rate).toFixed(1)}%`);

/** A row of table cells with these texts. */
export function row(texts) {
  const tr = document.createElement('tr');
  for (const text of texts) {
    const td = document.createElement('td');
    td.textContent = text;
    tr.append(td);
  }
  return tr;
}
