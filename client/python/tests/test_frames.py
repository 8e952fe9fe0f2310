"""Frame streams against a real server: identity-ordered and unordered frames, channels,
decimation and position bits, checked against known scene properties and against the Rust
client (floectl exporting the same recording); recordings, DataFrames and VTK files."""

from __future__ import annotations

import pathlib
import subprocess

import numpy as np
import pytest

import floe_client
from conftest import FLOECTL, SMALL_PARTICLES, frame_at

CHANNELS = ["velocity", "density", "pressure"]


def sorted_rows(a: np.ndarray) -> np.ndarray:
    return a[np.lexsort(a.T[::-1])]


def test_identity_frames_carry_positions_and_channels(client: floe_client.Client, scene: floe_client.SceneInfo) -> None:
    with client.frames(scene, channels=CHANNELS) as frames:
        first = next(frames)
        h = first.header
        assert (h.scene_id, h.step, h.time, h.mode, h.keyframe) == (scene.scene_id, 0, 0.0, "identity", True)
        assert h.particle_count == SMALL_PARTICLES
        assert list(first.channels) == ["position", *CHANNELS]
        assert first.positions.shape == (SMALL_PARTICLES, 3) and first.positions.dtype == np.float32
        assert first["velocity"].shape == (SMALL_PARTICLES, 3)
        for name in ("density", "pressure"):
            assert first[name].shape == (SMALL_PARTICLES,) and first[name].dtype == np.float32
        units = {c.name: c.unit for c in first.channels.values()}
        assert units == {"position": "m", "velocity": "m/s", "density": "kg/m^3", "pressure": "Pa"}

        # The column at rest on its lattice: a/h = 10 x 20 x 5 particles 5 cm apart, inside
        # [0, 0.5] x [0, 1] x [0, 0.25], not moving. (Densities and pressures are 0 until the
        # first step evaluates them.)
        p, err = first.positions, first.channels["position"].max_error
        assert np.all(p.min(axis=0) >= -np.array(err)) and np.all(p.max(axis=0) <= [0.5, 1.0, 0.25])
        assert len(np.unique(np.round(p[:, 0], 3))) == 10 and len(np.unique(np.round(p[:, 1], 3))) == 20
        np.testing.assert_allclose(first["velocity"], 0.0, atol=max(first.channels["velocity"].max_error))

        info = client.step(scene, 4)
        later = frame_at(frames, 4)
        assert later.header.time == info.sim_time and not later.header.keyframe
        # Falling (four steps of the preset's DFSPH: 0.02 s, before the collapse pushes the
        # column's foot up): every particle moved down or stayed, none up by more than the error.
        dy = later.positions[:, 1] - first.positions[:, 1]
        assert dy.min() < -1e-4 and dy.max() <= 2 * err[1]
        assert later["velocity"][:, 1].mean() < 0
        # Summation density is the rest density inside the column (1000 kg/m^3: the particle
        # mass comes from the lattice), less at the free surface, never much more.
        density = later["density"]
        assert abs(np.median(density) - 1000.0) < 2.0 and density.max() < 1010.0 and density.min() > 500.0


def test_unordered_and_decimated_frames_hold_the_same_particles(
    client: floe_client.Client, scene: floe_client.SceneInfo
) -> None:
    client.step(scene, 10)
    with client.frames(scene) as identity, client.frames(scene, mode="unordered") as unordered:
        full = frame_at(identity, 10)
        spatial = frame_at(unordered, 10)
    with client.frames(scene, decimation=7) as decimated:
        every7 = frame_at(decimated, 10)
    with client.frames(scene, bits=10) as coarse_stream:
        coarse = frame_at(coarse_stream, 10)

    assert spatial.header.mode == "unordered" and spatial.header.keyframe
    assert spatial.positions.shape == full.positions.shape
    # The same 16-bit grid over the scene bounds: the same positions, in another order.
    np.testing.assert_array_equal(sorted_rows(spatial.positions), sorted_rows(full.positions))

    assert every7.positions.shape == (len(range(0, SMALL_PARTICLES, 7)), 3)
    np.testing.assert_array_equal(every7.positions, full.positions[::7])

    err16, err10 = full.channels["position"].max_error, coarse.channels["position"].max_error
    assert all(e10 > 50 * e16 for e10, e16 in zip(err10, err16))
    np.testing.assert_allclose(coarse.positions, full.positions, rtol=0, atol=max(err10) + max(err16))


def test_a_view_culls_frames_and_a_watched_stream_changes_it(
    client: floe_client.Client, scene: floe_client.SceneInfo
) -> None:
    client.step(scene, 2)
    with client.frames(scene) as identity:
        full = frame_at(identity, 2)
    # The column's first four layers (x <= 0.2 m of 0.025 .. 0.475 m), by id.
    box = floe_client.View(box=((-1, -1, -1), (0.2, 5, 5)))
    with client.frames(scene, view=box) as boxed:
        inside = frame_at(boxed, 2)
    expected = np.flatnonzero(full.positions[:, 0] <= 0.2)
    np.testing.assert_array_equal(inside.ids, expected)
    np.testing.assert_array_equal(inside.positions, full.positions[expected])

    with client.watch_frames(scene, view=floe_client.View(budget=30)) as watched:
        assert len(frame_at(watched, 2).positions) == 30
        watched.set_view(floe_client.View(camera=floe_client.Camera((-1, 0.5, 0.125), (1, 0, 0), 60), budget=100))
        client.step(scene, 1)
        near = frame_at(watched, 3)
        assert len(near.positions) == 100
        watched.set_view(floe_client.View(budget=0, camera=floe_client.Camera((0, 0, 0), (0, 0, 0))))
        client.step(scene, 1)
        with pytest.raises(floe_client.InvalidArgument) as e:
            frame_at(watched, 4)
        assert e.value.field == "view.camera.direction"
    with client.frames(scene) as fixed, pytest.raises(floe_client.FailedPrecondition):
        fixed.set_view(None)


def test_bad_stream_options_name_the_field(client: floe_client.Client, scene: floe_client.SceneInfo) -> None:
    with pytest.raises(floe_client.InvalidArgument) as e:
        next(client.frames(scene, bits=20))
    assert e.value.field == "position_bits"
    with pytest.raises(floe_client.InvalidArgument) as e:
        next(client.frames(scene, decimation=5000))
    assert e.value.field == "decimation"
    with pytest.raises(floe_client.InvalidArgument, match="it has velocity, density, pressure") as e:
        next(client.frames(scene, channels=["temperature"]))
    assert e.value.field == "channels"
    with pytest.raises(ValueError, match="known: unordered, identity"):
        client.frames(scene, mode="sorted")
    with pytest.raises(floe_client.NotFound):
        next(client.frames(987654))


def _step_of(raw: bytes) -> int:
    # The simulation step, a u64 at byte 40 of the frame header (see floe-proto's header docs).
    return int.from_bytes(raw[40:48], "little")


def test_values_match_the_rust_client_and_export(
    client: floe_client.Client, scene: floe_client.SceneInfo, tmp_path: pathlib.Path
) -> None:
    rec = tmp_path / "run.rec"
    with client.frames(scene, channels=CHANNELS) as frames, floe_client.recording.Recorder(rec) as recorder:
        for target in (0, 5, 15):
            if target:
                client.step(scene, target - client.get(scene).steps)
            while True:
                raw = frames.next_raw()
                recorder.push(raw)
                if _step_of(raw) == target:
                    break
    ours = list(floe_client.recording.read(rec))
    assert [f.header.step for f in ours][-1] == 15 and ours[0].header.keyframe

    for fmt in ("csv", "vtk"):
        subprocess.run(
            [FLOECTL, "export", "--recording", rec, "--out", tmp_path / fmt, "--format", fmt],
            check=True,
            capture_output=True,
        )
    for k, frame in enumerate(ours):
        csv = tmp_path / "csv" / f"frame_{k:05}.csv"
        table = np.genfromtxt(csv, delimiter=",", names=True, dtype=np.float32)
        cols = floe_client.export.columns(frame)
        for name, (values, _) in cols.items():
            np.testing.assert_array_equal(values, table[name], err_msg=f"frame {k}: {name}")
        ours_vtk = tmp_path / f"ours_{k}.vtk"
        frame.write_vtk(ours_vtk)
        theirs = (tmp_path / "vtk" / f"frame_{k:05}.vtk").read_bytes()
        assert ours_vtk.read_bytes() == theirs, f"frame {k}: VTK differs from floectl export's"


def test_dataframe_has_a_column_per_component_with_units(
    client: floe_client.Client, scene: floe_client.SceneInfo
) -> None:
    with client.frames(scene, channels=["velocity", "density"]) as frames:
        frame = next(frames)
    df = frame.to_dataframe()
    assert list(df.columns) == ["x", "y", "z", "velocity_x", "velocity_y", "velocity_z", "density"]
    assert len(df) == SMALL_PARTICLES and df.index.name == "id"
    assert df.attrs["units"]["x"] == "m" and df.attrs["units"]["velocity_y"] == "m/s"
    assert df.attrs["units"]["density"] == "kg/m^3" and df.attrs["header"] == frame.header
    np.testing.assert_array_equal(df["y"].to_numpy(), frame.positions[:, 1])


def test_recordings_need_their_header(tmp_path: pathlib.Path) -> None:
    bad = tmp_path / "bad.rec"
    bad.write_bytes(b"NOTAREC!")
    with pytest.raises(ValueError, match="not a Floe recording"):
        list(floe_client.recording.read(bad))
    cut = tmp_path / "cut.rec"
    cut.write_bytes(floe_client.recording.MAGIC + (100).to_bytes(4, "little") + b"short")
    with pytest.raises(ValueError, match="frame 0 is cut short"):
        list(floe_client.recording.read(cut))


def test_a_solid_streams_as_its_own_set(client: floe_client.Client) -> None:
    """The floating blocks' two elastic cubes are the set ``solid``, the water ``fluid``:
    parts of ``particles`` whose frames carry the particles' ids, together all of them."""
    scene = client.create_preset("floating_blocks", ["particle_spacing=0.04"])
    try:
        sets = {s.name: s for s in scene.sets}
        assert (sets["solid"].part_of, sets["fluid"].part_of, sets["particles"].part_of) == (
            "particles",
            "particles",
            "",
        )
        ids = {}
        for name in ("particles", "solid", "fluid"):
            with client.frames(scene, channels=["velocity"], particle_set=name) as frames:
                frame = next(frames)
            assert frame.header.particle_set == name
            ids[name] = frame.ids if frame.ids is not None else np.arange(frame.header.particle_count)
            assert frame["velocity"].shape == (len(ids[name]), 3)
            if name == "solid":
                df = frame.to_dataframe()
                assert list(df.index) == list(frame.ids) and "ids" not in df.columns
        assert len(ids["solid"]) == sets["solid"].count > 0
        np.testing.assert_array_equal(np.sort(np.concatenate([ids["solid"], ids["fluid"]])), ids["particles"])
    finally:
        client.delete(scene)
