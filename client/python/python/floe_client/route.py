"""Following a scene to its worker in a cluster (several ``floe serve --worker`` behind one
proxy), as the Rust client does. A worker that does not hold a scene answers UNAVAILABLE with
the holder's name in the ``floe-worker`` trailing metadata, having done nothing; the call is
sent again naming that worker (the proxy routes on the header), which is remembered for the
scene's later calls. A call that finds no worker (the remembered one stopped, its scenes not
yet taken up elsewhere) is sent again, forgetting the worker, for up to :data:`FOLLOW_FOR`
seconds if it only reads; a call that changes the scene is not repeated blindly. On a single
server none of this happens.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any, TypeVar

import grpc

#: The request header (gRPC metadata) naming the worker a call is for.
WORKER_HEADER = "floe-worker"
#: Seconds a reading call keeps looking for a scene's worker (more than the default lease, 10 s).
FOLLOW_FOR = 30.0
#: Times a call is sent on to a named worker before the answer is returned (no proxy in front).
MOST_HOPS = 3

T = TypeVar("T")


def named_worker(e: grpc.RpcError) -> str | None:
    """The worker an UNAVAILABLE answer names, if any."""
    if e.code() != grpc.StatusCode.UNAVAILABLE:  # type: ignore[attr-defined]
        return None
    for key, value in e.trailing_metadata() or ():  # type: ignore[attr-defined]
        if key == WORKER_HEADER:
            return str(value)
    return None


class Routes:
    """Each scene's worker as last named by the cluster; the key None is a new scene's."""

    def __init__(self) -> None:
        self._workers: dict[int | None, str] = {}

    def metadata(self, target: int | None) -> tuple[tuple[str, str], ...]:
        """The header naming ``target``'s worker, when one is known."""
        worker = self._workers.get(target)
        return ((WORKER_HEADER, worker),) if worker else ()

    def forget(self, target: int | None) -> str | None:
        """Forgets and returns ``target``'s worker."""
        return self._workers.pop(target, None)

    def remember(self, target: int | None, worker: str) -> None:
        """Remembers ``worker`` for ``target``."""
        self._workers[target] = worker

    def call(self, target: int | None, reads: bool, send: Callable[[tuple[tuple[str, str], ...]], T]) -> T:
        """``send(extra_metadata)``, following the cluster's answers; raises the last error."""
        hops, started = 0, time.monotonic()
        while True:
            try:
                return send(self.metadata(target))
            except grpc.RpcError as e:
                worker = named_worker(e)
                if worker is not None:
                    hops += 1
                    self.remember(target, worker)
                    if hops <= MOST_HOPS:
                        continue
                elif e.code() == grpc.StatusCode.UNAVAILABLE:  # type: ignore[attr-defined]
                    # No worker answered (the named one stopped): the next call asks any
                    # worker again. A read waits for the cluster to move the scene (which
                    # names the stopped worker until its lease runs out, so the hops start
                    # again); a change raises for its caller to retry.
                    self.forget(target)
                    if reads and time.monotonic() - started < FOLLOW_FOR:
                        hops = 0
                        time.sleep(0.25)
                        continue
                raise


def scene_of(request: Any) -> int | None:
    """The scene a request is about (its ``scene_id``), or None for a new scene."""
    return getattr(request, "scene_id", None)
