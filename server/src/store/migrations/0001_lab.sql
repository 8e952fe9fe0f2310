-- Users, their API tokens (hashes only), quota overrides, scenes and share links.
-- Portable SQL: the same statements run on SQLite and PostgreSQL (BIGINT for
-- integers and flags, TEXT for names and JSON, DOUBLE PRECISION for floats).

CREATE TABLE users (
    name TEXT PRIMARY KEY,
    admin BIGINT NOT NULL,
    created_at BIGINT NOT NULL
);

-- SHA-256 of each API token, hex; the token itself is shown once and never stored.
CREATE TABLE tokens (
    hash TEXT PRIMARY KEY,
    user_name TEXT NOT NULL REFERENCES users (name) ON DELETE CASCADE,
    created_at BIGINT NOT NULL
);

-- Per-user overrides of the server-wide quota defaults (`floe serve --quota`).
CREATE TABLE quotas (
    user_name TEXT NOT NULL REFERENCES users (name) ON DELETE CASCADE,
    quota TEXT NOT NULL,
    value BIGINT NOT NULL,
    PRIMARY KEY (user_name, quota)
);

-- Every scene a user created and has not deleted. `spec` is the resolved scene at
-- creation, `tunables` the live settings now (a JSON object, path -> value); the
-- particle state lives in checkpoint files beside the database.
CREATE TABLE scenes (
    id BIGINT PRIMARY KEY,
    owner TEXT NOT NULL,
    name TEXT NOT NULL,
    spec TEXT NOT NULL,
    tunables TEXT NOT NULL,
    state TEXT NOT NULL,
    real_time_factor DOUBLE PRECISION NOT NULL,
    created_at BIGINT NOT NULL,
    updated_at BIGINT NOT NULL
);

-- Read-only share links (SHA-256 of the link's token, hex).
CREATE TABLE shares (
    hash TEXT PRIMARY KEY,
    scene_id BIGINT NOT NULL REFERENCES scenes (id) ON DELETE CASCADE,
    created_at BIGINT NOT NULL
);

-- Counters: the next scene id (ids are never reused), and the version of the
-- users, tokens, quotas and shares, bumped by every change so a running server
-- notices changes made by `floe admin`.
CREATE TABLE meta (
    name TEXT PRIMARY KEY,
    value BIGINT NOT NULL
);
INSERT INTO meta (name, value) VALUES ('next_scene_id', 1);
INSERT INTO meta (name, value) VALUES ('directory_version', 1);
