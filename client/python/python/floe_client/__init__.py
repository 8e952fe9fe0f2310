"""Python client of Floe, the particle-simulation server.

    import floe_client

    with floe_client.connect("http://127.0.0.1:50051") as floe:
        scene = floe.create_preset("dam_break", {"particle_spacing": 0.025})
        floe.run(scene)
        with floe.frames(scene, channels=["velocity"]) as frames:
            for frame in frames:
                print(frame.header.time, frame.positions.shape, frame["velocity"].mean(axis=0))
                break

Calls mirror the Rust client (floe-client); frames are decoded by floe-proto, the codec the
server encodes with, into numpy arrays. Units are SI.
"""

from . import export, local, notebook, recording
from .client import DEFAULT_ADDRESS, Client, connect
from .errors import (
    FailedPrecondition,
    FloeError,
    InvalidArgument,
    NotFound,
    PermissionDenied,
    ResourceExhausted,
    Unauthenticated,
    Unavailable,
)
from .frames import FORMAT_VERSION, Channel, DecodeError, Decoder, Frame, Header
from .messages import (
    Deleted,
    Event,
    Halted,
    ParameterChanged,
    Preset,
    SceneInfo,
    SceneStats,
    ShareLink,
    StepAbandoned,
)
from .streams import EventStream, FrameStream
from .view import Camera, View

__all__ = [
    "DEFAULT_ADDRESS",
    "FORMAT_VERSION",
    "Camera",
    "Channel",
    "Client",
    "DecodeError",
    "Decoder",
    "Deleted",
    "Event",
    "EventStream",
    "FailedPrecondition",
    "FloeError",
    "Frame",
    "FrameStream",
    "Halted",
    "Header",
    "InvalidArgument",
    "NotFound",
    "ParameterChanged",
    "PermissionDenied",
    "Preset",
    "ResourceExhausted",
    "SceneInfo",
    "SceneStats",
    "ShareLink",
    "StepAbandoned",
    "Unauthenticated",
    "Unavailable",
    "View",
    "connect",
    "export",
    "local",
    "notebook",
    "recording",
]
