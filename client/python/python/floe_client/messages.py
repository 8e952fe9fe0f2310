"""What the server answers, as typed values: scenes, statistics and events. Units are SI
(metres, seconds, kilograms, pascals), as in ``proto/floe/v1/scenes.proto``.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
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
    #: For a part of another set ("solid" and "fluid" of "particles"): that set, whose channels it
    #: offers; its particles move between parts as they change phase (ice melting), keeping their
    #: ids, which its identity-ordered frames carry. Empty for a set of its own.
    part_of: str = ""


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
class Preset:
    """A built-in preset: its name for :meth:`Client.create_preset`, and what it is."""

    name: str
    #: One line on what it is and what it reproduces, with its reference.
    about: str


@dataclass(frozen=True)
class Material:
    """A material of a scene, in the order of the ``material`` channel's indices."""

    name: str
    #: "fluid" or "solid".
    kind: str
    #: Rest density (kg/m^3).
    rest_density: float
    #: How viewers draw it when no channel colours it: "water", "snow", "ice" or "solid".
    look: str


@dataclass(frozen=True)
class Sizing:
    """The resolution a server chose for a preset created without a ``particle_spacing``
    (``floe serve --preset-size auto``): the finest spacing its backend stepped at real
    time or faster, and the preset's own (full) size."""

    #: The chosen particle spacing (m).
    spacing: float
    #: Particles at that spacing.
    particles: int
    #: Simulated seconds per wall second measured at that spacing, stepped alone.
    real_time_factor: float
    #: The preset's own spacing (m): create it with ``{"particle_spacing": full_spacing}`` for its full size.
    full_spacing: float
    #: Particles at the full size.
    full_particles: int


@dataclass(frozen=True, repr=False)
class SceneInfo:
    """One scene as the server sees it. Its repr is short (id, name, state, particles,
    time); ``scene`` holds the whole document."""

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
    #: The resolution the server chose for a preset created without one; None for a
    #: scene its creator sized (or a server that keeps presets at their own size).
    sizing: Sizing | None = None
    #: The scene's materials, in the order of the "material" channel's indices.
    materials: tuple[Material, ...] = ()
    #: The user who created it ("local" on a single-user server).
    owner: str = ""
    #: The scene in the server's browser viewer (``<viewer>/#scene=ID``) when the client
    #: knows the viewer's address (``connect(viewer=...)``, or ``local.Server.connect()``);
    #: "" otherwise. A server with users asks the viewer for a token.
    viewer_url: str = field(default="", compare=False)

    def __repr__(self) -> str:
        return (
            f"SceneInfo(scene_id={self.scene_id}, name={self.name!r}, state={self.state!r}, "
            f"particles={self.particles}, sim_time={self.sim_time:.6g})"
        )

    @classmethod
    def from_message(cls, m: pb.SceneInfo, viewer: str = "") -> SceneInfo:
        """The scene of a message; ``viewer``: the server's viewer address, for ``viewer_url``."""
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
            sets=tuple(
                ParticleSet(s.name, s.count, s.index, s.grid, s.look, s.surface, s.shade, s.part_of) for s in m.sets
            ),
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
            sizing=sizing(m.sizing) if m.HasField("sizing") else None,
            materials=tuple(Material(x.name, x.kind, x.rest_density, x.look) for x in m.materials),
            owner=m.owner,
            viewer_url=f"{viewer.rstrip('/')}/#scene={m.scene_id}" if viewer else "",
        )


def sizing(m: pb.Sizing) -> Sizing:
    return Sizing(m.spacing, m.particles, m.real_time_factor, m.full_spacing, m.full_particles)


@dataclass(frozen=True)
class Measure:
    """A value a scene's scheme or modules measured at its last step."""

    #: e.g. "fluid.kinetic_energy", "max_density_deviation", "dfsph.mean_iterations".
    name: str
    value: float
    #: SI unit; "" when dimensionless.
    unit: str


@dataclass(frozen=True, repr=False)
class SceneStats:
    """Throughput and streaming statistics of a scene, and what its scheme and modules
    measured at the last step (``measures``: kinetic energy in J, the largest density
    deviation, solver iterations, ...)."""

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
    #: What the scheme and modules measured at the last step, by name.
    measures: dict[str, Measure] = field(default_factory=dict)
    #: The scene's name.
    name: str = ""
    #: Encoded frame bytes sent to subscribers so far.
    frame_bytes: int = 0
    #: In a cluster, the worker holding the scene; "" on a single server.
    worker: str = ""

    def __repr__(self) -> str:
        return (
            f"SceneStats(scene_id={self.scene_id}, state={self.state!r}, sim_time={self.sim_time:.6g}, "
            f"steps={self.steps}, particles={self.particles}, steps_per_second={self.steps_per_second:.4g})"
        )

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
            measures={x.name: Measure(x.name, x.value, x.unit) for x in m.measures},
            name=m.name,
            frame_bytes=m.frame_bytes,
            worker=m.worker,
        )


@dataclass(frozen=True, repr=False)
class ShareLink:
    """A read-only share link of a scene (``Client.share``)."""

    scene_id: int
    #: Names the link, to list and revoke it.
    share_id: str
    #: The credential a viewer presents; shown only once.
    token: str

    def __repr__(self) -> str:
        return f"ShareLink(scene_id={self.scene_id}, share_id={self.share_id!r}, token=...)"


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
class StepAbandoned:
    """A step call's caller left (a cancelled call, a closed connection): the server
    learned it at ``left_at_step``, finished the step under way and left the scene
    paused at ``stopped_at_step`` (at most one step more)."""

    scene_id: int
    left_at_step: int
    stopped_at_step: int


@dataclass(frozen=True)
class Deleted:
    """The scene was deleted (or the server is shutting down); its streams end."""

    scene_id: int


Event = Halted | ParameterChanged | StepAbandoned | Deleted


def event(m: pb.SceneEvent) -> Event | None:
    """The event of a message; None for a kind this client does not know."""
    kind = m.WhichOneof("kind")
    if kind == "halted":
        h = m.halted
        particle = h.particle if h.HasField("particle") else None
        return Halted(m.scene_id, h.step, h.sim_time, h.reason, particle)
    if kind == "parameter_changed":
        return ParameterChanged(m.scene_id, tuple(m.parameter_changed.overrides))
    if kind == "step_abandoned":
        s = m.step_abandoned
        return StepAbandoned(m.scene_id, s.left_at_step, s.stopped_at_step)
    if kind == "deleted":
        return Deleted(m.scene_id)
    return None
