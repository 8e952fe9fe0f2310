"""Fixtures: a real `floe serve` on free ports (the debug build tests/run-all.sh makes, or
FLOE_BIN), clients of it, and small scenes.
"""

from __future__ import annotations

import os
import pathlib
import time
from collections.abc import Callable, Iterator

import pytest

import floe_client

ROOT = pathlib.Path(__file__).resolve().parents[3]
FLOE = pathlib.Path(os.environ.get("FLOE_BIN", ROOT / "target" / "debug" / "floe"))
FLOECTL = pathlib.Path(os.environ.get("FLOECTL_BIN", ROOT / "target" / "debug" / "floectl"))
GOLDEN = ROOT / "proto" / "testdata"

#: A dam break of 10 x 20 x 5 = 1,000 particles: quick to step on either backend.
SMALL = {"particle_spacing": 0.05}
SMALL_PARTICLES = 1000


def start(backend: str) -> floe_client.local.Server:
    if not FLOE.exists():
        pytest.fail(f"{FLOE} is missing: build it with `cargo build -p floe-server` (or set FLOE_BIN)")
    return floe_client.local.Server(FLOE, backend=backend)


@pytest.fixture(scope="session")
def server() -> Iterator[floe_client.local.Server]:
    """A server whose scenes step on the CPU backend."""
    with start("cpu") as s:
        yield s


@pytest.fixture(scope="session")
def gpu_server() -> Iterator[floe_client.local.Server]:
    """A server on the GPU backend (lavapipe where there is no GPU). Without any Vulkan
    adapter the tests using it skip, unless FLOE_REQUIRE_GPU=1 (as in tests/run-all.sh)."""
    try:
        s = start("gpu")
    except RuntimeError as e:
        if os.environ.get("FLOE_REQUIRE_GPU") == "1":
            raise
        pytest.skip(f"no GPU backend: {str(e).splitlines()[0]}")
    with s:
        yield s


@pytest.fixture
def client(server: floe_client.local.Server) -> Iterator[floe_client.Client]:
    with floe_client.connect(server.address) as c:
        yield c


@pytest.fixture
def scene(client: floe_client.Client) -> Iterator[floe_client.SceneInfo]:
    """A small paused dam break, deleted afterwards."""
    info = client.create_preset("dam_break", SMALL)
    yield info
    try:
        client.delete(info)
    except floe_client.NotFound:
        pass


def wait_for(condition: Callable[[], bool], what: str, timeout: float = 30.0) -> None:
    deadline = time.monotonic() + timeout
    while not condition():
        if time.monotonic() > deadline:
            pytest.fail(f"timed out waiting for {what}")
        time.sleep(0.02)


def frame_at(frames: floe_client.FrameStream, step: int) -> floe_client.Frame:
    """The first frame of the stream taken at simulation step `step` (or later: fails)."""
    for frame in frames:
        if frame.header.step == step:
            return frame
        assert frame.header.step < step, f"frame at step {frame.header.step}, expected one at {step}"
    pytest.fail(f"the stream ended before step {step}")
