// Following a scene to its worker in a cluster (several `floe serve --worker` behind one
// proxy). The proxy sends `/w/WORKER/...` to that worker and anything else to any worker; a
// worker asked about a scene (or a new scene) that another holds answers 421 with that
// worker's name, having done nothing, and the call is sent again through `/w/WORKER/`. The
// scene list names each scene's worker. On a single server no list names a worker and no
// answer is 421, so every path stays as it was.

/** The scene a REST path is about (`/scenes/7/step` -> 7), or 'new' for a new scene. */
export function sceneOf(path) {
  const m = /^\/scenes\/(\d+)(?:\/|$)/.exec(path);
  if (m) return Number(m[1]);
  return path === '/scenes' ? 'new' : null;
}

/** Each scene's worker, as the lists and the workers' answers name it. */
export class Routes {
  constructor() {
    this.workers = new Map();
  }

  /** Takes the workers a scene list names. */
  learn(scenes) {
    for (const s of scenes) if (s.worker) this.workers.set(s.scene_id, s.worker);
  }

  /** The URL path of API path `path` (`/scenes/7/ws`): through its scene's worker when known. */
  url(path) {
    const worker = this.workers.get(sceneOf(path));
    return worker ? `/w/${worker}/api/v1${path}` : `/api/v1${path}`;
  }

  /**
   * Sends `path` with `fetchFn` (the page's `fetch`), following a 421's worker at most
   * three times; a new scene's worker is then remembered under the scene's id.
   */
  async fetch(fetchFn, path, init) {
    const key = sceneOf(path);
    for (let hop = 0; ; hop += 1) {
      const r = await fetchFn(this.url(path), init);
      if (r.status !== 421 || hop >= 3 || key === null) {
        if (key === 'new' && r.ok) {
          // The worker that built it holds it; the next new scene is placed afresh.
          const created = await r.clone().json();
          const worker = created.worker ?? this.workers.get('new');
          if (worker) this.workers.set(created.scene_id, worker);
          this.workers.delete('new');
        }
        return r;
      }
      const body = await r.clone().json().catch(() => ({}));
      if (!body.worker) return r;
      this.workers.set(key, body.worker);
    }
  }
}
