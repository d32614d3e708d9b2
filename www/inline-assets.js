// The first lines of a build that carries its files inline (the offline
// file, the package's compat entry and widget: tools/bundle.mjs): each
// file, gzipped and in base64, becomes a data: URL, and the map of them by
// path is what module.js's assetUrl() answers from. data: URLs, not Blob
// URLs: a page opened from file:// has an opaque origin, and Chromium
// neither starts a module worker from its Blob URL nor lets a worker fetch
// one; a data: URL is both started and fetched (tests/bundle/offline.mjs).

/** A blob as a data: URL. */
const dataUrl = (blob) =>
  new Promise((resolve, reject) => {
    const reader = new FileReader();
    reader.onload = () => resolve(reader.result);
    reader.onerror = () => reject(reader.error);
    reader.readAsDataURL(blob);
  });

/**
 * Turns `{ path: { type, gzip } }` (`gzip`: the file gzipped, in base64)
 * into data: URLs and installs them as `globalThis.__REDUNDANT_IK_ASSETS__`
 * (once per page: a second build on the same page reuses the first's).
 */
export async function installAssets(files) {
  if (globalThis.__REDUNDANT_IK_ASSETS__) return;
  const entries = await Promise.all(
    Object.entries(files).map(async ([path, { type, gzip }]) => {
      const packed = Uint8Array.from(atob(gzip), (c) => c.charCodeAt(0));
      const stream = new Blob([packed]).stream().pipeThrough(new DecompressionStream('gzip'));
      const bytes = await new Response(stream).arrayBuffer();
      return [path, await dataUrl(new Blob([bytes], { type }))];
    }),
  );
  globalThis.__REDUNDANT_IK_ASSETS__ ??= Object.freeze(Object.fromEntries(entries));
}
