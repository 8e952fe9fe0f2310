"""A module's grid streamed to Python: the tests' tracer module (tests/tests/tracer/),
compiled into `floe_traced` (`cargo build -p floe-tests --example floe_traced`), counts
the particles above each of its 8 x 1 x 8 columns; its frames are grid frames whose
cells change as the dam break flows."""

from __future__ import annotations

import os
import pathlib

import numpy as np
import pytest

import floe_client
from conftest import ROOT, SMALL, SMALL_PARTICLES

TRACED = pathlib.Path(os.environ.get("FLOE_TRACED_BIN", ROOT / "target" / "debug" / "examples" / "floe_traced"))


def test_a_grid_streams_as_cells_that_change() -> None:
    if not TRACED.exists():
        pytest.fail(f"{TRACED} is missing: build it with `cargo build -p floe-tests --example floe_traced`")
    with floe_client.local.Server(TRACED, backend="cpu") as server, floe_client.connect(server.address) as client:
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
