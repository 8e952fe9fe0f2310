"""Server streams as Python iterators: decoded frames and scene events. Each ends when the
server ends it (the scene was deleted, the server stopped) or when closed; a stream is also
a context manager that closes it.
"""

from __future__ import annotations

import queue
from collections.abc import Callable, Iterator
from typing import Any, Generic, TypeVar

import grpc

from . import messages
from ._proto import scenes_pb2 as pb
from .errors import FailedPrecondition, FloeError, NotFound, from_rpc
from .frames import Decoder, Frame
from .view import View

T = TypeVar("T")

#: Codes a server answers a stream with (the request or the caller was refused), as
#: opposed to a lost connection.
_ANSWERS = frozenset(
    {
        grpc.StatusCode.NOT_FOUND,
        grpc.StatusCode.INVALID_ARGUMENT,
        grpc.StatusCode.PERMISSION_DENIED,
        grpc.StatusCode.UNAUTHENTICATED,
        grpc.StatusCode.RESOURCE_EXHAUSTED,
        grpc.StatusCode.FAILED_PRECONDITION,
        grpc.StatusCode.OUT_OF_RANGE,
    }
)


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

    def __init__(
        self,
        call: Any,
        decoder: Decoder,
        reopen: Callable[[], Any] | None = None,
        views: Views | None = None,
    ) -> None:
        super().__init__(call)
        self._decoder = decoder
        self._reopen = reopen
        self._views = views
        #: Frames skipped so far because this reader was slower than the scene.
        self.skipped = 0

    def set_view(self, view: View | None) -> None:
        """Changes the view of a stream from ``Client.watch_frames`` from the next frame on
        (None: every particle again). A bad view ends the stream: the next read raises
        :class:`InvalidArgument` naming the field."""
        if self._views is None:
            message = "set_view: this stream's view is fixed; open it with watch_frames"
            raise FailedPrecondition(grpc.StatusCode.FAILED_PRECONDITION, message)
        self._views.send(view.to_message() if view is not None else pb.FrameView())

    def close(self) -> None:
        if self._views is not None:
            self._views.end()
        super().close()

    def __next__(self) -> Frame:
        return self._decoder.decode(self.next_raw())

    def next_raw(self) -> bytes:
        """The next frame as the server encoded it, undecoded (to record it). Once read raw,
        a stream's later identity-ordered frames decode only from the next keyframe.

        In a cluster, a stream that breaks (its worker stopped) or ends while the scene lives
        on (it moved to another worker) is opened again where the scene is now, starting
        with a whole frame."""
        while True:
            try:
                message = self._next_message()
            except StopIteration:
                if self._closed or self._reopen is None or not self._moved():
                    raise
                continue
            except FloeError as e:
                if self._reopen is None or e.code in _ANSWERS or not self._moved():
                    raise
                continue
            self.skipped += message.skipped
            return bytes(message.data)

    def _moved(self) -> bool:
        """Opens the stream again where the scene is; False if the scene is gone."""
        assert self._reopen is not None
        try:
            self._call = self._reopen()
        except NotFound:
            return False
        self._decoder.reset()
        return True


class Views:
    """A watched stream's views (``Client.watch_frames``): its request, whose view is the one in
    force (a stream opened again starts with it), and the queue its call's later requests are
    read from (None ends them)."""

    def __init__(self, request: pb.StreamFramesRequest) -> None:
        self.request = request
        self.queue: queue.Queue[pb.FrameView | None] = queue.Queue()

    def send(self, view: pb.FrameView) -> None:
        """Sends ``view`` on the call and keeps it for a call opened again."""
        self.request.view.CopyFrom(view)
        self.queue.put(view)

    def end(self) -> None:
        """Ends the call's requests."""
        self.queue.put(None)

    def restart(self) -> None:
        """Ends the call's requests and starts a fresh queue for the next call (the old call's
        reader may still be waiting on the old one)."""
        self.end()
        self.queue = queue.Queue()


class EventStream(_Stream[messages.Event]):
    """Events of one scene (``Client.events``): Halted, ParameterChanged, StepAbandoned, Deleted."""

    def __next__(self) -> messages.Event:
        while True:
            e = messages.event(self._next_message())
            if e is not None:
                return e
