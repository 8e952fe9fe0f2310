"""A full create-step-stream round trip on each backend the server offers, the GPU's
frames checked against the CPU's (the CPU backend is the GPU's oracle)."""

from __future__ import annotations

import numpy as np
import pytest

import floe_client
from conftest import SMALL, SMALL_PARTICLES, frame_at

STEPS = 10


def round_trip(address: str, backend: str) -> floe_client.Frame:
    with floe_client.connect(address) as client:
        scene = client.create_preset("dam_break", SMALL)
        assert scene.backend == backend and scene.particles == SMALL_PARTICLES
        with client.frames(scene, channels=["velocity", "density"]) as frames:
            start = next(frames)
            assert start.header.step == 0
            info = client.step(scene, STEPS)
            frame = frame_at(frames, STEPS)
        assert frame.header.time == info.sim_time
        # The column has started to fall.
        assert (frame.positions[:, 1] - start.positions[:, 1]).min() < -1e-5
        client.delete(scene)
        return frame


def test_round_trip_on_the_gpu_matches_the_cpu(
    server: floe_client.local.Server, gpu_server: floe_client.local.Server
) -> None:
    cpu = round_trip(server.address, "cpu")
    gpu = round_trip(gpu_server.address, "gpu")
    # Only f32 rounding separates the backends (the adaptive time step too): after 10 steps
    # the positions agree to well under a millimetre, velocities to a few mm/s, densities
    # to a fraction of a percent.
    assert gpu.header.time == pytest.approx(cpu.header.time, rel=1e-5)
    np.testing.assert_allclose(gpu.positions, cpu.positions, rtol=0, atol=1e-4)
    np.testing.assert_allclose(gpu["velocity"], cpu["velocity"], rtol=0, atol=5e-3)
    np.testing.assert_allclose(gpu["density"], cpu["density"], rtol=1e-3)
