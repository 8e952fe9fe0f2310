-- A cluster: several `floe serve --worker NAME` sharing this database (PostgreSQL)
-- and one checkpoint directory. A single server never writes these rows, and its
-- scenes keep `worker` NULL.

-- Every worker that is up. `epoch` is unique over the cluster (from
-- meta.next_epoch) and new at each start, so what a stopped process holds can be
-- told from what its successor holds; `beats` counts heartbeats (others judge a
-- worker silent by their own clocks, so no two machines' clocks are compared).
CREATE TABLE workers (
    name TEXT PRIMARY KEY,
    epoch BIGINT NOT NULL,
    grpc TEXT NOT NULL,
    http TEXT NOT NULL,
    backend TEXT NOT NULL,
    max_scenes BIGINT NOT NULL,
    max_particles BIGINT NOT NULL,
    beats BIGINT NOT NULL,
    draining BIGINT NOT NULL,
    started_at BIGINT NOT NULL
);

-- A scene's placement: the worker holding it and that worker's epoch. Every write
-- for the scene names both, so a worker that lost the scene writes nothing.
ALTER TABLE scenes ADD COLUMN worker TEXT;
ALTER TABLE scenes ADD COLUMN epoch BIGINT NOT NULL DEFAULT 0;
-- Particles, for placement by free capacity and the cluster's running quotas.
ALTER TABLE scenes ADD COLUMN particles BIGINT NOT NULL DEFAULT 0;

INSERT INTO meta (name, value) VALUES ('next_epoch', 1);
