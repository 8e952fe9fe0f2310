"""The tests' tracer module (tests/tests/tracer/), compiled into `floe_traced`
(`cargo build -p floe-tests --example floe_traced`), streamed to Python: its grid (the
particles above each of 8 x 1 x 8 columns) as grid frames whose cells change as the dam
break flows, and its births and deaths as identity-ordered frames that name their
particles' ids."""

from __future__ import annotations

import os
import pathlib

import numpy as np
import pytest

import floe_client
from conftest import ROOT, SMALL, SMALL_PARTICLES

TRACED = pathlib.Path(os.environ.get("FLOE_TRACED_BIN", ROOT / "target" / "debug" / "examples" / "floe_traced"))


def traced() -> floe_client.local.Server:
    if not TRACED.exists():
        pytest.fail(f"{TRACED} is missing: build it with `cargo build -p floe-tests --example floe_traced`")
    return floe_client.local.Server(TRACED, backend="cpu")


def test_a_grid_streams_as_cells_that_change() -> None:
    with traced() as server, floe_client.connect(server.address) as client:
        scene = client.create_preset("dam_break", {**SMALL, "modules": ["fluid", "tracer"]})
        columns = next(s for s in scene.sets if s.name == "columns")
        assert columns.grid and columns.count == 64
        assert not next(s for s in scene.sets if s.name == "particles").grid
        counts = []
        for steps in (1, 40):
            client.step(scene, steps)
            with client.frames(scene, channels=["column_count"], particle_set="columns") as frames:
                frame = next(frames)
            h = frame.header
            assert h.mode == "grid" and h.particle_count == 64
            origin, size, dims = h.grid
            assert dims == (8, 1, 8) and all(s > 0 for s in size)
            assert "position" not in frame.channels
            values = frame["column_count"]
            err = max(frame.channels["column_count"].max_error)
            assert values.shape == (64,)
            assert abs(values.sum() - SMALL_PARTICLES) <= 64 * err
            counts.append(values)
        assert np.abs(counts[1] - counts[0]).max() > 1.0, "the columns change as the water flows"


def test_identity_frames_of_particles_born_and_dying_name_their_ids() -> None:
    # Every step replaces all particles with 500 born at rest (lifetime 0): the third
    # step's are ids 2000 to 2499.
    births = {"births": 500, "lifetime": 0}
    with traced() as server, floe_client.connect(server.address) as client:
        scene = client.create_preset("dam_break", {**SMALL, "modules": ["fluid", "tracer"], "tracer": births})
        client.step(scene, 3)
        with client.frames(scene, channels=["velocity"]) as frames:
            frame = next(frames)
            assert frame.header.mode == "identity" and frame.header.particle_count == 500
            ids = frame["ids"]
            assert ids.dtype == np.uint32
            np.testing.assert_array_equal(ids, np.arange(2000, 2500, dtype=np.uint32))
            assert frame.positions.shape == (500, 3)
            client.step(scene, 1)
            later = next(frames)
            assert later.header.keyframe
            np.testing.assert_array_equal(later["ids"], np.arange(2500, 3000, dtype=np.uint32))
