"""Server streams as Python iterators: decoded frames and scene events. Each ends when the
server ends it (the scene was deleted, the server stopped) or when closed; a stream is also
a context manager that closes it.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any, Generic, TypeVar

import grpc

from . import messages
from .errors import from_rpc
from .frames import Decoder, Frame

T = TypeVar("T")


class _Stream(Generic[T]):
    """A server-streaming call read one message at a time."""

    def __init__(self, call: Any) -> None:
        self._call = call
        self._closed = False

    def _next_message(self) -> Any:
        """The next message; StopIteration at the end or after :meth:`close`."""
        if self._closed:
            raise StopIteration
        try:
            return next(self._call)
        except grpc.RpcError as e:
            if self._closed and e.code() == grpc.StatusCode.CANCELLED:  # type: ignore[attr-defined]
                raise StopIteration from None
            raise from_rpc(e) from None

    def close(self) -> None:
        """Ends the stream; the server stops sending."""
        self._closed = True
        self._call.cancel()

    def __iter__(self) -> Iterator[T]:
        return self  # type: ignore[return-value]

    def __enter__(self: Any) -> Any:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


class FrameStream(_Stream[Frame]):
    """Decoded frames of one scene, in order (``Client.frames``).

    Latest-frame semantics: a reader slower than the scene skips frames, counted in
    :attr:`skipped`, and never slows the solver.
    """

    def __init__(self, call: Any, decoder: Decoder) -> None:
        super().__init__(call)
        self._decoder = decoder
        #: Frames skipped so far because this reader was slower than the scene.
        self.skipped = 0

    def __next__(self) -> Frame:
        return self._decoder.decode(self.next_raw())

    def next_raw(self) -> bytes:
        """The next frame as the server encoded it, undecoded (to record it). Once read raw,
        a stream's later identity-ordered frames decode only from the next keyframe."""
        message = self._next_message()
        self.skipped += message.skipped
        return bytes(message.data)


class EventStream(_Stream[messages.Event]):
    """Events of one scene (``Client.events``): Halted, ParameterChanged, Deleted."""

    def __next__(self) -> messages.Event:
        while True:
            e = messages.event(self._next_message())
            if e is not None:
                return e
