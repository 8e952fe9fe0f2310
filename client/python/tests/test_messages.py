"""What a scene's info and stats carry from the server's messages, and reprs short enough
to print in a notebook (the whole document stays in ``SceneInfo.scene``), and every kind
of event."""

from __future__ import annotations

import floe_client
from floe_client._proto import scenes_pb2 as pb
from floe_client.messages import Material, Measure, SceneInfo, SceneStats, Sizing, event


def test_scene_info_carries_sizing_materials_and_owner_and_prints_short() -> None:
    document = '{"name": "bunny", "fluids": [' + '{"blocks": []},' * 200 + "{}]}"
    m = pb.SceneInfo(
        scene_id=3,
        name="bunny",
        state=pb.SCENE_STATE_PAUSED,
        particles=2113,
        scene_json=document,
        owner="ada",
        # Floats of the wire (f32) that a double holds exactly.
        sizing=pb.Sizing(
            spacing=0.015625, particles=2113, real_time_factor=1.25, full_spacing=0.0078125, full_particles=6537
        ),
        materials=[pb.MaterialDescription(name="ice", kind="solid", rest_density=917.0, look="ice")],
    )
    info = SceneInfo.from_message(m)
    assert info.sizing == Sizing(0.015625, 2113, 1.25, 0.0078125, 6537)
    assert info.materials == (Material("ice", "solid", 917.0, "ice"),)
    assert info.owner == "ada"
    assert repr(info) == "SceneInfo(scene_id=3, name='bunny', state='paused', particles=2113, sim_time=0)"
    # A scene its creator sized has no sizing.
    assert SceneInfo.from_message(pb.SceneInfo(scene_id=4)).sizing is None


def test_scene_stats_carry_the_measures_by_name_and_print_short() -> None:
    m = pb.SceneStats(
        scene_id=3,
        name="bunny",
        steps=10,
        measures=[pb.Measure(name="fluid.kinetic_energy", value=0.5, unit="J")],
        frame_bytes=1234,
    )
    stats = SceneStats.from_message(m)
    assert stats.measures == {"fluid.kinetic_energy": Measure("fluid.kinetic_energy", 0.5, "J")}
    assert (stats.name, stats.frame_bytes) == ("bunny", 1234)
    assert repr(stats).startswith("SceneStats(scene_id=3, state=")
    assert "measures" not in repr(stats)


def test_every_event_kind_converts() -> None:
    events = [
        pb.SceneEvent(scene_id=3, halted=pb.Halted(step=7, sim_time=0.5, reason="too fast", particle=11)),
        pb.SceneEvent(scene_id=3, parameter_changed=pb.ParameterChanged(overrides=["gravity=[0,-1,0]"])),
        pb.SceneEvent(scene_id=3, step_abandoned=pb.StepAbandoned(left_at_step=40, stopped_at_step=41)),
        pb.SceneEvent(scene_id=3, deleted=pb.Deleted()),
    ]
    assert [event(m) for m in events] == [
        floe_client.Halted(3, 7, 0.5, "too fast", 11),
        floe_client.ParameterChanged(3, ("gravity=[0,-1,0]",)),
        floe_client.StepAbandoned(3, 40, 41),
        floe_client.Deleted(3),
    ]
    assert event(pb.SceneEvent(scene_id=3)) is None
