"""Exceptions: every failed call raises a :class:`FloeError` carrying the gRPC status code
and the server's message, which for bad input names the field, e.g.
``fluids[0].rest_density: must be > 0, got -3``.
"""

from __future__ import annotations

import re

import grpc

# A field path at the start of a line of the server's message: `name`, `a.b`, `fluids[0].x`.
_FIELD = re.compile(r"^([A-Za-z_]\w*(?:\[\d+\])*(?:\.[A-Za-z_]\w*(?:\[\d+\])*)*): ", re.MULTILINE)


class FloeError(Exception):
    """A call the server refused, or that could not reach it.

    Attributes:
        code: the gRPC status code (``grpc.StatusCode``).
        message: the server's message; a scene with several bad fields has one line each.
        fields: the field paths the message names, in order (empty if it names none).
    """

    def __init__(self, code: grpc.StatusCode, message: str) -> None:
        super().__init__(f"{message} ({code.name})")
        self.code = code
        self.message = message
        self.fields: tuple[str, ...] = tuple(_FIELD.findall(message))

    @property
    def field(self) -> str | None:
        """The first field path the message names, or None."""
        return self.fields[0] if self.fields else None


class InvalidArgument(FloeError, ValueError):
    """Bad input: a scene document, an override, a parameter or a stream option."""


class NotFound(FloeError, LookupError):
    """No scene has that id (or it was deleted)."""


class FailedPrecondition(FloeError):
    """The scene is not in a state that allows the call (e.g. stepping a running or halted scene)."""


class ResourceExhausted(FloeError):
    """Over a server limit: scenes, particles, message size."""


class Unavailable(FloeError, ConnectionError):
    """The server cannot be reached, or went away."""


class Unauthenticated(FloeError, PermissionError):
    """A lab server needs a token and got none, or one it does not know (revoked, mistyped)."""


class PermissionDenied(FloeError, PermissionError):
    """The token is known but may not do this (an admin-only call, a share link steering)."""


_BY_CODE: dict[grpc.StatusCode, type[FloeError]] = {
    grpc.StatusCode.INVALID_ARGUMENT: InvalidArgument,
    grpc.StatusCode.NOT_FOUND: NotFound,
    grpc.StatusCode.FAILED_PRECONDITION: FailedPrecondition,
    grpc.StatusCode.RESOURCE_EXHAUSTED: ResourceExhausted,
    grpc.StatusCode.UNAVAILABLE: Unavailable,
    grpc.StatusCode.UNAUTHENTICATED: Unauthenticated,
    grpc.StatusCode.PERMISSION_DENIED: PermissionDenied,
}


def error(code: grpc.StatusCode, message: str) -> FloeError:
    """The exception for a status: the subclass for its code, else :class:`FloeError`."""
    return _BY_CODE.get(code, FloeError)(code, message)


def from_rpc(e: grpc.RpcError) -> FloeError:
    """The exception for a failed gRPC call."""
    return error(e.code(), e.details() or "")  # type: ignore[attr-defined]
