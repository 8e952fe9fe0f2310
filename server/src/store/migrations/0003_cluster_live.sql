-- What each worker's scenes are doing as of its last heartbeat (a JSON list of
-- their figures), so any worker can show the whole cluster (floectl top, /metrics).
ALTER TABLE workers ADD COLUMN live TEXT NOT NULL DEFAULT '[]';

-- Room taken by placements whose scene has no row yet (it is being built, or its
-- creator is on the way to the worker placement named), so placements made at the
-- same time see each other. A reservation ends when its scene's row is inserted, or
-- once its worker has beaten `until_beats` times (each worker's own counter, so no
-- two machines' clocks are compared). Ids come from meta.next_reservation, whose
-- update also makes placements take turns.
CREATE TABLE reservations (
    id BIGINT PRIMARY KEY,
    worker TEXT NOT NULL,
    epoch BIGINT NOT NULL,
    particles BIGINT NOT NULL,
    until_beats BIGINT NOT NULL
);

INSERT INTO meta (name, value) VALUES ('next_reservation', 1);

-- How many times a scene moved between workers. Its checkpoint files carry it in
-- their names and rank by it first, so a file a stopped worker names after the
-- scene moved never ranks above the new worker's.
ALTER TABLE scenes ADD COLUMN generation BIGINT NOT NULL DEFAULT 0;
