"""The calls of ``floe.v1.SceneService``, mirroring the Rust client (floe-client)."""

from __future__ import annotations

import builtins
import json
import os
import pathlib
from collections.abc import Iterable, Iterator, Mapping, Sequence
from typing import Any

import grpc

from ._proto import scenes_pb2 as pb
from ._proto import scenes_pb2_grpc as pb_grpc
from .errors import Unavailable, from_rpc
from .frames import Decoder
from .messages import Preset, SceneInfo, SceneStats, ShareLink
from .route import Routes, scene_of
from .streams import EventStream, FrameStream, Views
from .view import View

#: Where :func:`connect` goes without an address: ``FLOE_SERVER`` or this (as floectl).
DEFAULT_ADDRESS = "http://127.0.0.1:50051"

#: Largest message accepted (bytes): snapshots of large scenes (as the Rust client).
MAX_MESSAGE_BYTES = 512 << 20

#: "key=value" overrides, or a mapping whose values are written as JSON
#: (``{"gravity": [0, -1.62, 0]}`` is ``gravity=[0, -1.62, 0]``).
Overrides = Sequence[str] | Mapping[str, Any]

#: A scene: its id, or what the server said about it.
SceneLike = int | SceneInfo


def _overrides(o: Overrides) -> list[str]:
    if isinstance(o, Mapping):
        return [f"{key}={json.dumps(value)}" for key, value in o.items()]
    if isinstance(o, str):
        raise TypeError("overrides: give a list of 'key=value' strings or a dict, not one string")
    return list(o)


def _id(scene: SceneLike) -> int:
    return scene.scene_id if isinstance(scene, SceneInfo) else int(scene)


def _enum_name(enum: Any, prefix: str, name: str, what: str) -> str:
    """``prefix + NAME``, checked to be in a proto enum; ValueError listing the names allowed."""
    try:
        enum.Value(prefix + name.upper())
        return prefix + name.upper()
    except ValueError:
        known = [n.removeprefix(prefix).lower() for n in enum.keys() if not n.endswith("UNSPECIFIED")]
        raise ValueError(f"{what}: unknown {name!r}; known: {', '.join(known)}") from None


def _target(address: str) -> tuple[str, bool]:
    """The gRPC target of an address and whether it wants TLS (``https://``)."""
    for scheme, tls in (("http://", False), ("https://", True)):
        if address.startswith(scheme):
            return address[len(scheme) :].rstrip("/"), tls
    return address, False


class Client:
    """A connection to a Floe server. Scene arguments take an id or a :class:`SceneInfo`.

    Every failed call raises a :class:`~floe_client.errors.FloeError` with the gRPC code and
    the server's message (bad input: :class:`~floe_client.errors.InvalidArgument`, naming the
    field in ``.field``).
    """

    def __init__(self, channel: grpc.Channel, token: str | None = None, viewer: str | None = None) -> None:
        """Wraps an open channel; :func:`connect` is the usual way in."""
        #: The server's browser viewer (``http://host:port``), when known: scenes then carry
        #: their ``viewer_url``.
        self.viewer = (viewer or "").rstrip("/")
        self._channel = channel
        self._stub = pb_grpc.SceneServiceStub(channel)
        self._lab = pb_grpc.LabServiceStub(channel)
        self._metadata = (("authorization", f"Bearer {token}"),) if token else ()
        # In a cluster, each scene's worker (floe_client.route).
        self._routes = Routes()

    def _call(self, method: str, request: Any, service: Any = None) -> Any:
        target = scene_of(request)
        stub = getattr(service or self._stub, method)
        try:
            reply = self._routes.call(
                target, method in _READS, lambda extra: stub(request, metadata=self._metadata + extra)
            )
        except grpc.RpcError as e:
            raise from_rpc(e) from None
        if method == "CreateScene":
            # The worker that built it holds it; the next new scene is placed afresh.
            self._routes.forget(None)
            if reply.worker:
                self._routes.remember(reply.scene_id, reply.worker)
        return reply

    def _info(self, m: pb.SceneInfo) -> SceneInfo:
        return SceneInfo.from_message(m, self.viewer)

    def close(self) -> None:
        """Closes the connection (its streams end)."""
        self._channel.close()

    def __enter__(self) -> Client:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # Creating scenes.

    # Every create call takes ``backend``: "gpu" or "cpu" for a scene that must run
    # on it ("" for any). A single server refuses a backend it does not run
    # (FailedPrecondition); a cluster places the scene on a worker that runs it.

    def create_preset(self, preset: str, overrides: Overrides = (), *, backend: str = "") -> SceneInfo:
        """A scene from a built-in preset ("dam_break", "hydrostatic") with overrides."""
        return self._create(pb.CreateSceneRequest(preset=preset, overrides=_overrides(overrides), backend=backend))

    def create_document(
        self, text: str, format: str = "toml", overrides: Overrides = (), *, backend: str = ""
    ) -> SceneInfo:
        """A scene from a scene document (``format``: "toml" or "json"; see ``floe schema``)."""
        request = pb.CreateSceneRequest(
            document=text, document_format=format, overrides=_overrides(overrides), backend=backend
        )
        return self._create(request)

    def create_file(self, path: str | os.PathLike[str], overrides: Overrides = (), *, backend: str = "") -> SceneInfo:
        """A scene from a ``.toml`` or ``.json`` scene file."""
        path = pathlib.Path(path)
        format = {".toml": "toml", ".json": "json"}.get(path.suffix.lower())
        if format is None:
            raise ValueError(f"{path}: a scene file ends in .toml or .json")
        return self.create_document(path.read_text(), format, overrides, backend=backend)

    def create_dict(self, scene: Mapping[str, Any], overrides: Overrides = (), *, backend: str = "") -> SceneInfo:
        """A scene from a dict shaped like a scene document (sent as JSON)."""
        return self.create_document(json.dumps(scene), "json", overrides, backend=backend)

    def _create(self, request: pb.CreateSceneRequest) -> SceneInfo:
        return self._info(self._call("CreateScene", request))

    # Inspecting and deleting.

    def get(self, scene: SceneLike) -> SceneInfo:
        """One scene (NotFound if no scene has that id)."""
        return self._info(self._call("GetScene", pb.SceneRef(scene_id=_id(scene))))

    def list(self) -> builtins.list[SceneInfo]:
        """Every scene on the server."""
        return [self._info(s) for s in self._call("ListScenes", pb.ListScenesRequest()).scenes]

    def presets(self) -> builtins.list[Preset]:
        """The built-in presets :meth:`create_preset` takes, each with a line on what it is
        (as ``floe presets`` prints them)."""
        return [Preset(p.name, p.about) for p in self._call("ListPresets", pb.ListPresetsRequest()).presets]

    def delete(self, scene: SceneLike) -> SceneInfo:
        """Deletes a scene; its frame and event streams end after a Deleted event."""
        return self._info(self._call("DeleteScene", pb.SceneRef(scene_id=_id(scene))))

    def stats(self, scene: SceneLike) -> SceneStats:
        """Throughput and streaming statistics."""
        return SceneStats.from_message(self._call("GetStats", pb.SceneRef(scene_id=_id(scene))))

    # Stepping.

    def step(self, scene: SceneLike, steps: int | None = None, *, until: float | None = None) -> SceneInfo:
        """Advances a paused scene by ``steps`` steps (1 to 1,000,000), or to simulated time
        ``until`` (s); returns when done."""
        if (steps is None) == (until is None):
            raise ValueError("step: give steps or until (s), not both or neither")
        request = pb.StepRequest(scene_id=_id(scene), steps=steps or 0, until_time=until or 0.0)
        return self._info(self._call("Step", request))

    def run(self, scene: SceneLike, real_time_factor: float = 0.0) -> SceneInfo:
        """Runs continuously at ``real_time_factor`` simulated seconds per wall second
        (0: as fast as the machine allows)."""
        request = pb.RunRequest(scene_id=_id(scene), real_time_factor=real_time_factor)
        return self._info(self._call("Run", request))

    def pause(self, scene: SceneLike) -> SceneInfo:
        """Stops a running scene after its current step."""
        return self._info(self._call("Pause", pb.SceneRef(scene_id=_id(scene))))

    def reset(self, scene: SceneLike) -> SceneInfo:
        """Puts a paused or halted scene back at t = 0 with its current settings."""
        return self._info(self._call("Reset", pb.SceneRef(scene_id=_id(scene))))

    def set_parameters(self, scene: SceneLike, overrides: Overrides) -> SceneInfo:
        """Changes tunable settings from the next step (gravity, fluids[i].viscosity,
        fluids[i].xsph, solver.time_step, solver.damping, solver.damping_until, guard);
        other fields are InvalidArgument."""
        request = pb.SetParametersRequest(scene_id=_id(scene), overrides=_overrides(overrides))
        return self._info(self._call("SetParameters", request))

    # State.

    def snapshot(self, scene: SceneLike) -> bytes:
        """The scene's complete state (particles, time, step control, statistics)."""
        return bytes(self._call("Snapshot", pb.SceneRef(scene_id=_id(scene))).state)

    def restore(self, scene: SceneLike, state: bytes) -> SceneInfo:
        """Replaces a paused scene's state with a :meth:`snapshot` of the same scene; it then
        steps on bit for bit as from where the snapshot was taken."""
        return self._info(self._call("Restore", pb.RestoreRequest(scene_id=_id(scene), state=state)))

    # Streams.

    def frames(
        self,
        scene: SceneLike,
        *,
        channels: Iterable[str] = (),
        fps: float = 30.0,
        bits: int = 16,
        decimation: int = 1,
        mode: str = "identity",
        particle_set: str = "",
        view: View | None = None,
    ) -> FrameStream:
        """Decoded frames of a scene as it steps, channels under the scene's names.

        Args:
            channels: extra channels besides positions, by name (``SceneInfo.channels`` lists
                the scene's: "velocity", "density", "pressure", and the modules').
            fps: most frames per second (up to 240).
            bits: bits per position axis, 8 to 16.
            decimation: send every n-th particle (particles 0, n, 2n, ...), 1 to 1000.
            mode: "identity" (particle i at index i) or "unordered" (smallest, spatial order).
            particle_set: the set to stream (``SceneInfo.sets``); "" for the SPH particles.
            view: a region of interest and a particle budget (:class:`View`); None sends every
                particle. Not with decimation above 1.
        """
        info = self.get(scene)
        request = _frames_request(scene, channels, fps, bits, decimation, mode, particle_set, view)
        return FrameStream(
            self._stream("StreamFrames", request), Decoder(scene=info), reopen=lambda: self._reopen(request)
        )

    def watch_frames(
        self,
        scene: SceneLike,
        *,
        channels: Iterable[str] = (),
        fps: float = 30.0,
        bits: int = 16,
        mode: str = "identity",
        particle_set: str = "",
        view: View | None = None,
    ) -> FrameStream:
        """As :meth:`frames`, on a stream whose view changes while it is open
        (:meth:`FrameStream.set_view`): a camera that moves through a large scene."""
        info = self.get(scene)
        request = _frames_request(scene, channels, fps, bits, 1, mode, particle_set, view)
        views = Views(request)
        return FrameStream(self._watch(views), Decoder(scene=info), reopen=lambda: self._rewatch(views), views=views)

    def share(self, scene: SceneLike) -> ShareLink:
        """A new read-only share link of a scene: its token lets a viewer watch the scene
        (frames, events, stats) but not steer it; the token is shown only here."""
        m = self._call("ShareScene", pb.SceneRef(scene_id=_id(scene)), self._lab)
        return ShareLink(m.scene_id, m.share_id, m.token)

    def show(self, scene: SceneLike, *, width: str | int = "100%", height: int = 480) -> Any:
        """The live viewer of a scene in a notebook cell, on a new read-only share link (see
        :func:`floe_client.notebook.show`); needs the viewer's address (``connect(viewer=...)``)."""
        from .notebook import show

        return show(self, scene, width=width, height=height)

    def events(self, scene: SceneLike) -> EventStream:
        """Events of a scene: Halted (with the reason), ParameterChanged, StepAbandoned, Deleted."""
        return EventStream(self._stream("StreamEvents", pb.SceneRef(scene_id=_id(scene))))

    def _stream(self, method: str, request: Any) -> Any:
        # A refused stream raises when first read; the stream maps that error. In a cluster it
        # is opened on the scene's worker as last known (the stream follows it when it moves).
        return getattr(self._stub, method)(request, metadata=self._metadata + self._routes.metadata(request.scene_id))

    def _reopen(self, request: pb.StreamFramesRequest) -> Any:
        """A frame stream opened again where the scene is now (after its worker stopped or
        it moved); raises NotFound if the scene is gone."""
        self.get(request.scene_id)
        return self._stream("StreamFrames", request)

    def _watch(self, views: Views) -> Any:
        """A WatchFrames call started with the stream's request, its later requests the
        views ``views`` is sent."""
        requests, start = views.queue, pb.WatchFramesRequest(start=views.request)

        def messages() -> Iterator[pb.WatchFramesRequest]:
            yield start
            while (view := requests.get()) is not None:
                yield pb.WatchFramesRequest(view=view)

        metadata = self._metadata + self._routes.metadata(views.request.scene_id)
        return self._stub.WatchFrames(messages(), metadata=metadata)

    def _rewatch(self, views: Views) -> Any:
        """A watched stream opened again where the scene is now, with its latest view."""
        self.get(views.request.scene_id)
        views.restart()
        return self._watch(views)


def _frames_request(
    scene: SceneLike,
    channels: Iterable[str],
    fps: float,
    bits: int,
    decimation: int,
    mode: str,
    particle_set: str,
    view: View | None,
) -> pb.StreamFramesRequest:
    """The request of a frame stream."""
    request = pb.StreamFramesRequest(
        scene_id=_id(scene),
        channel_names=list(channels),
        max_fps=fps,
        position_bits=bits,
        mode=_enum_name(pb.FrameMode, "FRAME_MODE_", mode, "mode"),
        decimation=decimation,
        particle_set=particle_set,
    )
    if view is not None:
        request.view.CopyFrom(view.to_message())
    return request


#: Calls that change nothing: sent again while a scene's worker is being found.
_READS = frozenset({"GetScene", "GetStats", "Snapshot", "ListScenes", "ListPresets"})


def connect(
    address: str | None = None, *, token: str | None = None, timeout: float = 10.0, viewer: str | None = None
) -> Client:
    """Connects to a Floe server.

    Args:
        address: ``http://host:port`` (or ``host:port``; ``https://`` for TLS); default
            ``FLOE_SERVER`` or ``http://127.0.0.1:50051``.
        token: sent as ``authorization: Bearer <token>`` with every call, for a server that
            admits users by token (the lab server).
        timeout: seconds to wait for the connection; then :class:`Unavailable`.
        viewer: the server's HTTP address (``http://host:8080``, where ``floe serve`` prints
            "Floe viewer: ..."); scenes then carry their ``viewer_url``.
    """
    address = address or os.environ.get("FLOE_SERVER") or DEFAULT_ADDRESS
    target, tls = _target(address)
    options = [("grpc.max_receive_message_length", MAX_MESSAGE_BYTES)]
    if tls:
        channel = grpc.secure_channel(target, grpc.ssl_channel_credentials(), options=options)
    else:
        channel = grpc.insecure_channel(target, options=options)
    try:
        grpc.channel_ready_future(channel).result(timeout=timeout)
    except grpc.FutureTimeoutError:
        channel.close()
        raise Unavailable(grpc.StatusCode.UNAVAILABLE, f"cannot connect to {address} within {timeout} s") from None
    return Client(channel, token, viewer)
