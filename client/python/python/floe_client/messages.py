"""What the server answers, as typed values: scenes, statistics and events. Units are SI
(metres, seconds, kilograms, pascals), as in ``proto/floe/v1/scenes.proto``.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from typing import Any

from ._proto import scenes_pb2 as pb


def _state(value: int) -> str:
    # SCENE_STATE_PAUSED -> "paused": the proto's names are the one list of states.
    return pb.SceneState.Name(value).removeprefix("SCENE_STATE_").lower()


@dataclass(frozen=True)
class ChannelInfo:
    """A per-particle quantity a scene offers."""

    #: Name to ask for (``Client.frames(channels=...)``).
    name: str
    #: Its tag in the frame format.
    tag: int
    #: SI unit; "" for an index.
    unit: str
    #: Values per particle.
    components: int
    #: The particle set it belongs to.
    set: str
    #: Sent exactly (uint8), not quantised.
    exact: bool
    #: What it holds.
    about: str
    #: The module that declares it.
    module: str


@dataclass(frozen=True)
class ParticleSet:
    """A particle set (or grid) of a scene."""

    name: str
    #: Particles (or cells) in it.
    count: int
    #: The set index its frames carry.
    index: int
    #: A grid: its frames are grid frames (``Frame.header.grid``, cells x fastest, no positions).
    grid: bool = False
    #: How viewers draw it (a material look's name, e.g. ``"snow"``); empty when the module says nothing.
    look: str = ""
    #: For a grid: the channel holding each cell's surface height (m); empty when none.
    surface: str = ""
    #: For a grid in a look: the channel (0 to 1) scaling how much of the look viewers draw; empty when none.
    shade: str = ""


@dataclass(frozen=True)
class Tunable:
    """A setting ``set_parameters`` may change, as an override path."""

    #: e.g. "gravity" or "fluids[*].xsph" ([*]: any index).
    path: str
    #: SI unit; "" for tables and dimensionless numbers.
    unit: str
    #: Bounds of a number, when it has them.
    min: float | None
    max: float | None
    about: str
    module: str


@dataclass(frozen=True)
class SceneInfo:
    """One scene as the server sees it."""

    scene_id: int
    name: str
    #: "paused", "running", "halted" or "deleted".
    state: str
    #: Simulated time (s).
    sim_time: float
    steps: int
    particles: int
    #: The domain particles may occupy (m); frames quantise positions over it.
    bounds_min: tuple[float, float, float]
    bounds_max: tuple[float, float, float]
    #: Why the stability guard halted the scene (state "halted"), else None.
    halt_reason: str | None
    #: The scene document as resolved, every default filled in (as from JSON).
    scene: dict[str, Any]
    #: The backend stepping it: "gpu" or "cpu".
    backend: str
    #: The channels frames can carry, with their units and tags.
    channels: tuple[ChannelInfo, ...] = ()
    #: The particle sets (and grids) frames can carry, with their counts.
    sets: tuple[ParticleSet, ...] = ()
    #: The settings ``set_parameters`` may change.
    tunables: tuple[Tunable, ...] = ()
    #: In a cluster, the worker holding the scene (the client follows it there); "" on a
    #: single server. A list gives the other workers' scenes by id, name, state, particles
    #: and worker only: ``get`` gives the rest.
    worker: str = ""

    @classmethod
    def from_message(cls, m: pb.SceneInfo) -> SceneInfo:
        return cls(
            scene_id=m.scene_id,
            name=m.name,
            state=_state(m.state),
            sim_time=m.sim_time,
            steps=m.steps,
            particles=m.particles,
            bounds_min=tuple(m.bounds_min),  # type: ignore[arg-type]
            bounds_max=tuple(m.bounds_max),  # type: ignore[arg-type]
            halt_reason=m.halt_reason or None,
            scene=json.loads(m.scene_json) if m.scene_json else {},
            backend=m.backend,
            channels=tuple(
                ChannelInfo(c.name, c.tag, c.unit, c.components, c.set, c.exact, c.about, c.module) for c in m.channels
            ),
            sets=tuple(ParticleSet(s.name, s.count, s.index, s.grid, s.look, s.surface, s.shade) for s in m.sets),
            tunables=tuple(
                Tunable(
                    t.path,
                    t.unit,
                    t.min if t.HasField("min") else None,
                    t.max if t.HasField("max") else None,
                    t.about,
                    t.module,
                )
                for t in m.tunables
            ),
            worker=m.worker,
        )


@dataclass(frozen=True)
class SceneStats:
    """Throughput and streaming statistics of a scene."""

    scene_id: int
    state: str
    #: Simulated time (s).
    sim_time: float
    steps: int
    particles: int
    #: Steps per wall second over the last second of stepping.
    steps_per_second: float
    #: The last time step (s).
    dt: float
    #: Open frame streams.
    subscribers: int
    #: Frames skipped by slow subscribers, summed over all of them.
    dropped_frames: int
    #: Frames published by the solver.
    frames_published: int

    @classmethod
    def from_message(cls, m: pb.SceneStats) -> SceneStats:
        return cls(
            scene_id=m.scene_id,
            state=_state(m.state),
            sim_time=m.sim_time,
            steps=m.steps,
            particles=m.particles,
            steps_per_second=m.steps_per_second,
            dt=m.dt,
            subscribers=m.subscribers,
            dropped_frames=m.dropped_frames,
            frames_published=m.frames_published,
        )


@dataclass(frozen=True)
class Halted:
    """The stability guard stopped the scene."""

    scene_id: int
    step: int
    #: Simulated time (s).
    sim_time: float
    reason: str
    #: Stable id of the particle that crossed the bound, when one did.
    particle: int | None


@dataclass(frozen=True)
class ParameterChanged:
    """Tunable settings changed (``Client.set_parameters``)."""

    scene_id: int
    #: The overrides applied, "key=value".
    overrides: tuple[str, ...]


@dataclass(frozen=True)
class Deleted:
    """The scene was deleted (or the server is shutting down); its streams end."""

    scene_id: int


Event = Halted | ParameterChanged | Deleted


def event(m: pb.SceneEvent) -> Event | None:
    """The event of a message; None for a kind this client does not know."""
    kind = m.WhichOneof("kind")
    if kind == "halted":
        h = m.halted
        particle = h.particle if h.HasField("particle") else None
        return Halted(m.scene_id, h.step, h.sim_time, h.reason, particle)
    if kind == "parameter_changed":
        return ParameterChanged(m.scene_id, tuple(m.parameter_changed.overrides))
    if kind == "deleted":
        return Deleted(m.scene_id)
    return None
