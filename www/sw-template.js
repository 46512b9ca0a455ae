// Service worker of the five-axis calculator (generated at build time from www/sw-template.js).
// It caches as the page goes: nothing is downloaded for it alone. Every file the page (or its
// workers) fetches through it is kept; files fetched before it took control (on the first visit)
// are copied from the browser's HTTP cache with `only-if-cached`, which never goes to the
// network. Assets are then served from the cache first, pages from the network first with the
// cache as fallback, so what a visit loaded works offline afterwards. It only ever touches
// requests to this page's own origin.
const CACHE = 'fiveaxis-__VERSION__';
/** Every file of this build (relative to this script): the candidates for the sweep. */
const ASSETS = __ASSETS__;

self.addEventListener('install', () => self.skipWaiting());

self.addEventListener('activate', (event) => {
  event.waitUntil(
    caches
      .keys()
      .then((keys) => Promise.all(keys.filter((k) => k.startsWith('fiveaxis-') && k !== CACHE).map((k) => caches.delete(k))))
      .then(() => self.clients.claim())
      .then(sweep),
  );
});

/** Copies into the cache the build's files that the HTTP cache holds and this cache lacks. */
async function sweep() {
  const cache = await caches.open(CACHE);
  await Promise.all(
    ASSETS.map(async (path) => {
      const url = new URL(path, self.location.href).href;
      if (await cache.match(url, { ignoreSearch: true })) return;
      try {
        const response = await fetch(url, { cache: 'only-if-cached', mode: 'same-origin' });
        if (response.ok) await cache.put(url, response);
      } catch {
        // Not in the HTTP cache: the page has not needed it yet.
      }
    }),
  );
}

// The page asks for a sweep once its first panel is up (the workers' files are then fetched).
self.addEventListener('message', (event) => {
  if (event.data === 'sweep') event.waitUntil(sweep());
});

function keep(request, response) {
  if (response.ok && response.type === 'basic') {
    const copy = response.clone();
    caches.open(CACHE).then((cache) => cache.put(request, copy));
  }
  return response;
}

self.addEventListener('fetch', (event) => {
  const request = event.request;
  if (request.method !== 'GET' || new URL(request.url).origin !== self.location.origin) return;
  if (request.mode === 'navigate') {
    event.respondWith(
      fetch(request)
        .then((response) => keep(new URL('./', self.location.href).href, response))
        .catch(() => caches.match('./').then((hit) => hit || caches.match(request, { ignoreSearch: true }))),
    );
    return;
  }
  event.respondWith(
    caches.match(request, { ignoreSearch: true }).then((hit) => hit || fetch(request).then((response) => keep(request, response))),
  );
});
