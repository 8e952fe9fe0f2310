"""The Python client and the REST API through a cluster's proxy (tests/cluster.sh starts
PostgreSQL, nginx and three workers on loopback and runs this with their addresses):
scenes created through the proxy land one on each worker, every call follows its scene
to its worker, and REST names a scene's worker and reaches it through /w/WORKER/.
Skipped without the cluster's addresses, unless FLOE_REQUIRE_CLUSTER=1.
"""

from __future__ import annotations

import json
import os
import time
import urllib.error
import urllib.request

import pytest

import floe_client

PROXY_GRPC = os.environ.get("FLOE_PROXY_GRPC")
PROXY_HTTP = os.environ.get("FLOE_PROXY_HTTP")

pytestmark = pytest.mark.skipif(
    not PROXY_GRPC and os.environ.get("FLOE_REQUIRE_CLUSTER") != "1",
    reason="no cluster (tests/cluster.sh runs this)",
)


def rest(path: str) -> tuple[int, dict | list]:
    try:
        with urllib.request.urlopen(f"{PROXY_HTTP}{path}", timeout=30) as r:
            return r.status, json.loads(r.read())
    except urllib.error.HTTPError as e:
        return e.code, json.loads(e.read())


def test_calls_follow_scenes_to_their_workers() -> None:
    assert PROXY_GRPC and PROXY_HTTP, "FLOE_REQUIRE_CLUSTER is set but FLOE_PROXY_GRPC is not"
    with floe_client.connect(PROXY_GRPC) as c:
        ids = [c.create_preset("hydrostatic", {"particle_spacing": 0.1}).scene_id for _ in range(3)]
        for i in ids:
            assert c.step(i, 3).steps == 3
            assert c.get(i).steps == 3
        deadline = time.monotonic() + 10
        while True:
            placed = {s.scene_id: s.worker for s in c.list() if s.scene_id in ids}
            if len(placed) == 3 and all(placed.values()):
                break
            assert time.monotonic() < deadline, f"the list does not name every scene's worker: {placed}"
            time.sleep(0.2)
        assert len(set(placed.values())) >= 2, f"new scenes spread over the workers: {placed}"

        # REST: the list names each worker; /w/WORKER/ reaches it; another worker says where.
        status, listed = rest("/api/v1/scenes")
        assert status == 200
        assert {s["scene_id"]: s.get("worker") for s in listed if s["scene_id"] in ids} == placed
        for i, worker in placed.items():
            status, scene = rest(f"/w/{worker}/api/v1/scenes/{i}")
            assert (status, scene["steps"]) == (200, 3)
            other = next(w for w in set(placed.values()) if w != worker)
            # Another worker names the holder (503 "not known yet" until its next tick, at most 1 s).
            deadline = time.monotonic() + 5
            while (answer := rest(f"/w/{other}/api/v1/scenes/{i}"))[0] == 503 and time.monotonic() < deadline:
                time.sleep(0.2)
            assert (answer[0], answer[1]["worker"]) == (421, worker), answer
        for i in ids:
            c.delete(i)
