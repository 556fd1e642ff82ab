// The viewer's service worker: keeps the page, the planner (script and wasm) and the example
// fields in a cache, so that the page opens and plans with no network once it has loaded.
// Requests go to the network first (an online page is always the newest) and fall back to the
// cache; every good response refreshes the cache. `precache.json` (written by
// scripts/site.mjs) lists the site's files, cached at install.
const CACHE = "furrow-viewer";

self.addEventListener("install", (event) => {
  event.waitUntil(
    (async () => {
      const response = await fetch("precache.json", { cache: "no-store" });
      const { files } = await response.json();
      const cache = await caches.open(CACHE);
      await cache.addAll(["./", ...files]);
      await self.skipWaiting();
    })(),
  );
});

self.addEventListener("activate", (event) => {
  event.waitUntil(self.clients.claim());
});

self.addEventListener("fetch", (event) => {
  const request = event.request;
  if (request.method !== "GET" || new URL(request.url).origin !== self.location.origin) return;
  event.respondWith(
    (async () => {
      const cache = await caches.open(CACHE);
      try {
        const response = await fetch(request, { cache: "no-store" });
        if (response.ok) await cache.put(request, response.clone());
        return response;
      } catch (e) {
        // The page's address may carry a field (#name) or a query: the page itself either way.
        const cached = (await cache.match(request, { ignoreSearch: true })) ?? (request.mode === "navigate" ? await cache.match("./") : undefined);
        if (cached) return cached;
        throw e;
      }
    })(),
  );
});
