"""Scene calls against a real server: create, inspect, step, run, pause, reset, set
parameters, snapshot and restore, statistics, events, and the errors of bad input."""

from __future__ import annotations

import json
import pathlib
import subprocess
import urllib.request

import grpc
import numpy as np
import pytest

import floe_client
from conftest import FLOE, ROOT, SMALL, SMALL_PARTICLES, frame_at, wait_for


def test_the_presets_are_listed_as_floe_presets_prints_them(client: floe_client.Client) -> None:
    printed = subprocess.run([FLOE, "presets"], capture_output=True, text=True, check=True).stdout.splitlines()
    listed = client.presets()
    assert [p.name for p in listed] == [line.split()[0] for line in printed]
    assert listed[0] == floe_client.Preset(listed[0].name, printed[0].split(None, 1)[1])


def test_create_from_a_preset_a_file_a_document_and_a_dict(client: floe_client.Client, tmp_path: pathlib.Path) -> None:
    preset = client.create_preset("dam_break", SMALL)
    assert (preset.name, preset.state, preset.particles, preset.steps, preset.sim_time) == (
        "dam_break",
        "paused",
        SMALL_PARTICLES,
        0,
        0.0,
    )
    assert preset.backend == "cpu" and preset.halt_reason is None
    assert preset.scene["particle_spacing"] == 0.05
    assert all(lo < hi for lo, hi in zip(preset.bounds_min, preset.bounds_max))

    column = ROOT / "examples" / "column.toml"
    from_file = client.create_file(column, ["particle_spacing=0.04"])
    assert from_file.name == "column" and from_file.scene["particle_spacing"] == 0.04

    from_document = client.create_document(column.read_text(), "toml", {"particle_spacing": 0.04})
    assert from_document.particles == from_file.particles

    as_dict = dict(from_file.scene, name="column from a dict")
    from_dict = client.create_dict(as_dict)
    assert from_dict.name == "column from a dict" and from_dict.particles == from_file.particles

    json_file = tmp_path / "column.json"
    json_file.write_text(json.dumps(as_dict))
    assert client.create_file(json_file).particles == from_file.particles

    ids = {s.scene_id for s in client.list()}
    created = [preset, from_file, from_document, from_dict]
    assert {s.scene_id for s in created} <= ids
    for s in created:
        assert client.get(s.scene_id) == client.get(s)
        deleted = client.delete(s)
        assert deleted.scene_id == s.scene_id
        with pytest.raises(floe_client.NotFound) as e:
            client.get(s)
        assert e.value.code == grpc.StatusCode.NOT_FOUND


def test_bad_input_raises_with_the_code_and_the_field(client: floe_client.Client) -> None:
    with pytest.raises(floe_client.InvalidArgument) as e:
        client.create_preset("dam_break", {"fluids[0].rest_density": -3})
    assert e.value.code == grpc.StatusCode.INVALID_ARGUMENT
    assert e.value.field == "fluids[0].rest_density"
    assert "must be > 0, got -3" in e.value.message
    assert isinstance(e.value, ValueError)

    # Several bad fields: each named, one per line.
    with pytest.raises(floe_client.InvalidArgument) as e:
        client.create_preset("dam_break", {"fluids[0].rest_density": -3, "particle_spacing": -1})
    assert set(e.value.fields) == {"fluids[0].rest_density", "particle_spacing"}

    with pytest.raises(floe_client.InvalidArgument, match="unknown preset 'nope'") as e:
        client.create_preset("nope")
    assert e.value.field is None

    with pytest.raises(floe_client.InvalidArgument) as e:
        client.create_document("name = ", "toml")
    with pytest.raises(floe_client.InvalidArgument) as e:
        client.create_document("{}", "yaml")
    assert e.value.field == "document_format"

    with pytest.raises(floe_client.NotFound):
        client.step(987654, 1)
    with pytest.raises(ValueError, match="ends in .toml or .json"):
        client.create_file("scene.yaml")
    with pytest.raises(TypeError):
        client.create_preset("dam_break", "particle_spacing=0.05")
    # The test server runs the CPU backend.
    with pytest.raises(floe_client.FailedPrecondition, match="runs its scenes on the cpu backend, not gpu") as e:
        client.create_preset("dam_break", ["particle_spacing=0.1"], backend="gpu")
    assert e.value.field == "backend"


def test_bad_step_and_run_arguments_name_the_field(client: floe_client.Client, scene: floe_client.SceneInfo) -> None:
    with pytest.raises(floe_client.InvalidArgument) as e:
        client.step(scene, 0)
    assert e.value.field == "steps"
    with pytest.raises(floe_client.InvalidArgument) as e:
        client.step(scene, until=-1.0)
    assert e.value.field == "until_time"
    with pytest.raises(floe_client.InvalidArgument) as e:
        client.run(scene, -2.0)
    assert e.value.field == "real_time_factor"
    with pytest.raises(ValueError, match="not both"):
        client.step(scene, 3, until=0.1)


def test_step_run_pause_and_reset(client: floe_client.Client, scene: floe_client.SceneInfo) -> None:
    stepped = client.step(scene, 10)
    assert stepped.steps == 10 and stepped.sim_time > 0 and stepped.state == "paused"
    until = client.step(scene, until=stepped.sim_time + 0.01)
    assert until.sim_time >= stepped.sim_time + 0.01 and until.steps > 10

    running = client.run(scene)
    assert running.state == "running"
    wait_for(lambda: client.stats(scene).steps > until.steps + 20, "the running scene to step")
    with pytest.raises(floe_client.FailedPrecondition, match="running"):
        client.step(scene, 1)
    paused = client.pause(scene)
    assert paused.state == "paused"
    assert client.get(scene).steps == paused.steps

    reset = client.reset(scene)
    assert (reset.steps, reset.sim_time, reset.state) == (0, 0.0, "paused")


def test_stats_count_steps_and_subscribers(client: floe_client.Client, scene: floe_client.SceneInfo) -> None:
    with client.frames(scene) as frames:
        next(frames)
        info = client.step(scene, 5)
        frame_at(frames, 5)
        stats = client.stats(scene)
        assert (stats.scene_id, stats.steps, stats.sim_time, stats.particles) == (
            scene.scene_id,
            5,
            info.sim_time,
            SMALL_PARTICLES,
        )
        assert stats.state == "paused" and stats.subscribers == 1
        assert stats.frames_published >= 1 and 0 < stats.dt < 0.01
    # The server notices a closed stream when it next has a frame for it.
    client.step(scene, 1)
    wait_for(lambda: client.stats(scene).subscribers == 0, "the closed stream to unsubscribe")


def test_set_parameters_applies_and_emits_an_event(client: floe_client.Client, scene: floe_client.SceneInfo) -> None:
    with client.events(scene) as events:
        info = client.set_parameters(scene, {"gravity": [0, -1.62, 0]})
        assert info.scene["gravity"] == pytest.approx([0, -1.62, 0])
        event = next(events)
        assert event == floe_client.ParameterChanged(scene.scene_id, ("gravity=[0, -1.62, 0]",))
    with pytest.raises(floe_client.InvalidArgument) as e:
        client.set_parameters(scene, ["particle_spacing=0.1"])
    assert e.value.field == "particle_spacing"


def test_snapshot_and_restore_step_on_bit_for_bit(client: floe_client.Client, scene: floe_client.SceneInfo) -> None:
    client.step(scene, 5)
    state = client.snapshot(scene)
    assert isinstance(state, bytes) and len(state) > SMALL_PARTICLES * 12
    with client.frames(scene, channels=["velocity"]) as frames:
        client.step(scene, 10)
        first = frame_at(frames, 15)
    restored = client.restore(scene, state)
    assert restored.steps == 5
    with client.frames(scene, channels=["velocity"]) as frames:
        client.step(scene, 10)
        again = frame_at(frames, 15)
    assert again.header.time == first.header.time
    np.testing.assert_array_equal(again.positions, first.positions)
    np.testing.assert_array_equal(again["velocity"], first["velocity"])

    with pytest.raises(floe_client.InvalidArgument):
        client.restore(scene, b"not a snapshot")


def test_events_report_halts_and_deletion(client: floe_client.Client) -> None:
    # A speed limit the falling column soon exceeds: the guard halts the scene.
    scene = client.create_preset("dam_break", {**SMALL, "guard.max_speed": 0.05})
    with client.events(scene) as events:
        info = client.step(scene, until=0.5)
        assert info.state == "halted" and "max_speed" in (info.halt_reason or "")
        halted = next(events)
        assert isinstance(halted, floe_client.Halted)
        assert halted.step == info.steps and halted.sim_time == info.sim_time
        assert halted.particle is not None and 0 <= halted.particle < SMALL_PARTICLES
        assert halted.reason.startswith("speed ") and halted.reason in info.halt_reason
        assert f"(particle {halted.particle})" in info.halt_reason
        with pytest.raises(floe_client.FailedPrecondition, match="halted"):
            client.step(scene, 1)
        client.delete(scene)
        assert next(events) == floe_client.Deleted(scene.scene_id)
        assert next(events, None) is None


def test_connect_fails_clearly_without_a_server() -> None:
    with pytest.raises(floe_client.Unavailable, match="cannot connect to http://127.0.0.1:9"):
        floe_client.connect("http://127.0.0.1:9", timeout=0.5)


def test_a_scene_knows_its_viewer_url_when_the_client_knows_the_viewer(
    server: floe_client.local.Server, scene: floe_client.SceneInfo
) -> None:
    with server.connect() as c:
        info = c.get(scene)
        assert info.viewer_url == f"{server.http.rstrip('/')}/#scene={scene.scene_id}"
        # The viewer serves the page the URL names.
        with urllib.request.urlopen(info.viewer_url.split("#")[0], timeout=10) as page:
            assert b"<html" in page.read(2048).lower()
    # A client told only the gRPC address does not know it.
    assert scene.viewer_url == ""
