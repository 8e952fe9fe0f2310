// The viewer's credential on a lab server: a user's API token or a share link's
// token, given once in the address's fragment (`/#token=...&scene=3`: a fragment
// never reaches the server or its logs), kept for this tab only (sessionStorage),
// and sent as `authorization: Bearer` on REST calls and as a WebSocket protocol
// (browsers cannot set headers on a WebSocket). A single-user server needs none.

const KEY = 'floe.token';

export class Credentials {
  /** Credentials kept in `storage` (sessionStorage in the page). */
  constructor(storage) {
    this.storage = storage;
  }

  /**
   * Takes `token` and `scene` from the fragment of `loc`, keeps the token and clears
   * the fragment from the address bar (so a copied address does not carry the token).
   * Returns the scene id asked for, if any.
   */
  readFragment(loc, history) {
    const params = new URLSearchParams(loc.hash.slice(1));
    const token = params.get('token');
    if (token) this.storage.setItem(KEY, token);
    if (params.has('token') || params.has('scene')) history.replaceState(null, '', loc.pathname + loc.search);
    const scene = Number(params.get('scene') ?? NaN);
    return Number.isInteger(scene) && scene > 0 ? scene : undefined;
  }

  /** Headers for a REST call. */
  headers() {
    const token = this.storage.getItem(KEY);
    return token ? { authorization: `Bearer ${token}` } : {};
  }

  /** Protocols for a WebSocket: the server selects `floe.v1` and reads the token. */
  protocols() {
    const token = this.storage.getItem(KEY);
    return token ? ['floe.v1', token] : ['floe.v1'];
  }
}
