"""Recordings: encoded frames in a file, the format ``floectl record`` writes and
``floectl export --recording`` reads: magic ``FLOEREC1``, then per frame a little-endian
u32 length and the frame's bytes. A recording starts with the first frame of a stream (a
keyframe), so identity-ordered delta frames replay with one decoder.
"""

from __future__ import annotations

import os
import struct
from collections.abc import Iterator
from typing import BinaryIO

from .frames import Decoder, Frame

MAGIC = b"FLOEREC1"
_LEN = struct.Struct("<I")


class Recorder:
    """Writes encoded frames (``FrameStream.next_raw``) to a recording file."""

    def __init__(self, path: str | os.PathLike[str]) -> None:
        self._out: BinaryIO = open(path, "wb")
        self._out.write(MAGIC)

    def push(self, frame: bytes) -> None:
        """Appends one encoded frame."""
        self._out.write(_LEN.pack(len(frame)))
        self._out.write(frame)

    def close(self) -> None:
        self._out.close()

    def __enter__(self) -> Recorder:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def read(path: str | os.PathLike[str]) -> Iterator[Frame]:
    """The frames of a recording, decoded in order."""
    decoder = Decoder()
    with open(path, "rb") as f:
        if f.read(len(MAGIC)) != MAGIC:
            raise ValueError(f"{path}: not a Floe recording (no FLOEREC1 header)")
        index = 0
        while prefix := f.read(_LEN.size):
            if len(prefix) < _LEN.size:
                raise ValueError(f"{path}: ends inside the length of frame {index}")
            (length,) = _LEN.unpack(prefix)
            data = f.read(length)
            if len(data) < length:
                raise ValueError(f"{path}: frame {index} is cut short ({len(data)} of {length} bytes)")
            yield decoder.decode(data)
            index += 1
