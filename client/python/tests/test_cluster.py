"""The Python client and the REST API through a cluster's proxy (tests/cluster.sh starts
PostgreSQL, nginx and three workers on loopback and runs this with their addresses):
scenes created through the proxy land one on each worker, every call follows its scene
to its worker, and REST names a scene's worker and reaches it through /w/WORKER/.
Skipped without the cluster's addresses, unless FLOE_REQUIRE_CLUSTER=1.
"""

from __future__ import annotations

import glob
import json
import os
import pathlib
import shlex
import shutil
import signal
import subprocess
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
        # (each worker learns of the others' new scenes at its next tick, within a second)
        deadline = time.monotonic() + 5
        while True:
            status, listed = rest("/api/v1/scenes")
            assert status == 200
            if {s["scene_id"]: s.get("worker") for s in listed if s["scene_id"] in ids} == placed:
                break
            assert time.monotonic() < deadline, f"the REST list does not name every scene's worker: {listed}"
            time.sleep(0.2)
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


def _as_postgres(*args: str) -> None:
    """Runs a PostgreSQL command as the postgres user when root (PostgreSQL refuses root)."""
    prefix = ["runuser", "-u", "postgres", "--"] if os.geteuid() == 0 else []
    subprocess.run([*prefix, *args], check=True, capture_output=True)


def test_restarting_postgresql_and_the_proxy_loses_no_scene() -> None:
    """PostgreSQL down for longer than the workers' lease, then nginx restarted: every scene
    is still on its worker, steps on, and no worker was evicted."""
    assert PROXY_GRPC and PROXY_HTTP, "FLOE_REQUIRE_CLUSTER is set but FLOE_PROXY_GRPC is not"
    cluster = pathlib.Path(os.environ["FLOE_CLUSTER_DIR"])
    pg_ctl = sorted(glob.glob("/usr/lib/postgresql/*/bin/pg_ctl"))[-1]
    with floe_client.connect(PROXY_GRPC) as c:
        created = [c.create_preset("hydrostatic", {"particle_spacing": 0.1}) for _ in range(3)]
        ids = [s.scene_id for s in created]
        c.run(ids[0], 1.0)
        before = {s.scene_id: s.worker for s in created}

        data = cluster / "pg" / "data"
        # The server's own options (port, socket directory), as it was started with them:
        # postmaster.opts is its command line, binary and data directory first.
        options = shlex.split((data / "postmaster.opts").read_text())[3:]
        _as_postgres(pg_ctl, "-D", str(data), "-m", "fast", "-w", "stop")
        time.sleep(6)  # twice the test cluster's lease (3 s)
        log = str(cluster / "pg" / "server.log")
        _as_postgres(pg_ctl, "-D", str(data), "-l", log, "-o", shlex.join(options), "-w", "start")

        nginx_dir = cluster / "nginx"
        old = int((nginx_dir / "nginx.pid").read_text())
        os.kill(old, signal.SIGTERM)
        while pathlib.Path(f"/proc/{old}").exists():
            time.sleep(0.1)
        nginx = shutil.which("nginx") or "/usr/sbin/nginx"
        proxy = subprocess.Popen([nginx, "-p", str(nginx_dir), "-c", str(nginx_dir / "nginx.conf")])
        (nginx_dir / "nginx.pid").write_text(f"{proxy.pid}\n")
        deadline = time.monotonic() + 20
        while True:
            try:
                listed = {s.scene_id: s.worker for s in c.list() if s.scene_id in ids}
                if listed == before:
                    break
            except floe_client.errors.FloeError:
                pass
            assert time.monotonic() < deadline, f"scenes {before} not all back on their workers"
            time.sleep(0.5)
        # A worker steps again once its heartbeat reaches the database (a step before is refused).
        for i in ids[1:]:
            deadline = time.monotonic() + 20
            while True:
                try:
                    assert c.step(i, 2).steps == 2
                    break
                except floe_client.errors.Unavailable:
                    assert time.monotonic() < deadline, f"scene {i} does not step again"
                    time.sleep(0.5)
        c.pause(ids[0])
        for i in ids:
            c.delete(i)
    logs = "".join(p.read_text() for p in cluster.glob("worker-*.log"))
    assert "evicted" not in logs, "a worker was evicted over a database outage"
