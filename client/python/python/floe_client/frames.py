"""Decoded particle frames. Frames are decoded by floe-proto, the Rust codec the server
encodes with (the ``_codec`` extension module), and every channel arrives as a numpy array
that owns the decoder's buffer: nothing is copied on the way.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from . import _codec

if TYPE_CHECKING:
    import os

    import pandas

    from .messages import SceneInfo

#: Raised for a frame that cannot be decoded (a ``ValueError``); its message says why.
DecodeError = _codec.DecodeError

#: The frame format version this package reads.
FORMAT_VERSION: int = _codec.FORMAT_VERSION


@dataclass(frozen=True)
class Header:
    """What a frame says about itself."""

    scene_id: int
    #: Position of the frame in its stream.
    sequence: int
    #: The frame an identity delta frame predicts from (equal to ``sequence`` otherwise).
    base_sequence: int
    #: Simulation step the frame was taken at.
    step: int
    #: Simulated time (s).
    time: float
    #: "identity" (particle i at index i in every frame) or "unordered" (spatial order).
    mode: str
    #: Whether the frame decodes on its own (every unordered frame does).
    keyframe: bool
    particle_count: int
    #: Bytes of the encoded frame.
    frame_len: int
    #: Frame format version.
    version: int
    #: Index of the particle set (or grid) the frame carries, in the scene's ``sets``.
    set: int
    #: The set's name when the scene is known (frames of ``Client.frames``), else None.
    particle_set: str | None = None
    #: A grid frame's grid: origin (m), size (m) and cells per axis (cells x fastest);
    #: None for particle frames.
    grid: tuple[tuple[float, float, float], tuple[float, float, float], tuple[int, int, int]] | None = None


@dataclass(frozen=True)
class Channel:
    """One per-particle quantity of a frame."""

    #: "position", "velocity", "density", ... (``SceneInfo.channels`` lists a scene's).
    name: str
    #: SI unit: "m", "m/s", "kg/m^3", "Pa", "K", ...; "" for material indices.
    unit: str
    #: ``(N, c)`` float32 for ``c`` components, ``(N,)`` float32 for one, ``(N,)`` uint8 for
    #: exact channels (material indices).
    values: np.ndarray
    #: Largest error quantisation introduced, per component, in ``unit``.
    max_error: tuple[float, ...]
    #: The channel's tag in the frame format (0-63 fixed, 64-255 assigned per scene).
    tag: int = 0


@dataclass(frozen=True)
class Frame:
    """A decoded frame: the header and the channels by name, positions first.

    In identity-ordered frames row i of every channel is particle i (of the particles sent:
    with decimation n, particle ``i * n``); in unordered frames rows are in spatial order,
    the same order in every channel.
    """

    header: Header
    channels: Mapping[str, Channel]

    @property
    def positions(self) -> np.ndarray:
        """Positions (m), ``(N, 3)`` float32."""
        return self.channels["position"].values

    @property
    def ids(self) -> np.ndarray | None:
        """The particles' stable ids, ``(N,)`` uint32 ascending, where the frame carries them:
        identity-ordered frames of a part of the particles (``ParticleSet.part_of``: a solid's
        particles, which melting moves to the fluid's) or of a set whose particles are born
        and die. None otherwise (row i of an identity frame is then particle i)."""
        ids = self.channels.get("ids")
        return None if ids is None else ids.values

    def __getitem__(self, name: str) -> np.ndarray:
        """The values of channel ``name``; KeyError naming the channels present if absent."""
        try:
            return self.channels[name].values
        except KeyError:
            raise KeyError(f"no channel {name!r} in this frame; it has {', '.join(self.channels)}") from None

    def to_dataframe(self) -> pandas.DataFrame:
        """The frame as a pandas DataFrame (see :func:`floe_client.export.to_dataframe`)."""
        from .export import to_dataframe

        return to_dataframe(self)

    def plot(self, channel: str | None = None, **options: Any) -> Any:
        """A still picture of the frame with matplotlib, coloured by ``channel`` (see
        :func:`floe_client.notebook.plot_frame` for the options). Returns the axes."""
        from .notebook import plot_frame

        return plot_frame(self, channel, **options)

    def write_vtk(self, path: str | os.PathLike[str]) -> None:
        """Writes the frame as a legacy VTK file (see :func:`floe_client.export.write_vtk`)."""
        from .export import write_vtk

        write_vtk(self, path)


class Decoder:
    """Decodes the frames of one stream, in order.

    Identity-ordered delta frames predict from the frame before, which the decoder holds;
    decoding one whose base it does not hold raises :data:`DecodeError` (decode from the
    stream's first frame, a keyframe). A frame that fails leaves the decoder as it was.
    """

    def __init__(
        self,
        max_particles: int | None = None,
        max_frame_bytes: int | None = None,
        *,
        scene: SceneInfo | None = None,
    ) -> None:
        """Frames over ``max_particles`` or ``max_frame_bytes`` are refused before anything is
        allocated for them (defaults: 16 Mi particles, 1 GiB). With ``scene``, channels and
        sets get the scene's names and units (a module's channels travel under per-scene tags
        that only the scene names)."""
        self._inner = _codec.Decoder(max_particles, max_frame_bytes)
        self._names = {c.tag: (c.name, c.unit) for c in scene.channels} if scene else {}
        self._sets = {s.index: s.name for s in scene.sets} if scene else {}

    def decode(self, data: bytes) -> Frame:
        """Decodes one encoded frame (bytes after its length are ignored)."""
        header, channels = self._inner.decode(data)
        header["particle_set"] = self._sets.get(header["set"])
        if header["grid"] is not None:
            header["grid"] = tuple(tuple(part) for part in header["grid"])
        named = {}
        for tag, name, unit, values, error in channels:
            name, unit = self._names.get(tag, (name, unit))
            named[name] = Channel(name, unit, values, error, tag)
        return Frame(header=Header(**header), channels=named)

    def reset(self) -> None:
        """Forgets the held frame, so that only a keyframe decodes next."""
        self._inner.reset()

    @property
    def last_sequence(self) -> int | None:
        """Sequence number of the last frame decoded."""
        return self._inner.last_sequence

    @property
    def held_sequence(self) -> int | None:
        """Sequence number of the identity-ordered frame delta frames can apply to."""
        return self._inner.held_sequence
