"""A ``floe serve`` on this machine, started on free ports: for notebooks, tests and
benchmarks that want a private server.

    with floe_client.local.Server("target/release/floe") as server:
        client = floe_client.connect(server.address)
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import tempfile
import time
from collections.abc import Sequence
from typing import IO

from .client import Client, connect

# The log line naming the gRPC listener, and the line printed once both listen.
_GRPC_LINE = re.compile(r"gRPC \(.*\) on (\S+)")
_READY_LINE = re.compile(r"Floe viewer: (http://\S+?)/?$")


class Server:
    """``floe serve --scene none`` on ``127.0.0.1:0`` (free ports) with the given backend,
    keeping its scenes in ``data_dir`` (by default a temporary directory removed on stop, so
    a private server neither sees nor leaves scenes in the user's own data directory).

    Attributes:
        address: the gRPC address, ``http://127.0.0.1:PORT``, for :func:`floe_client.connect`.
        http: the viewer's and REST API's base URL.
    """

    def __init__(
        self,
        floe: str | os.PathLike[str] = "floe",
        *,
        backend: str = "auto",
        args: Sequence[str] = (),
        data_dir: str | os.PathLike[str] | None = None,
        timeout: float = 60.0,
    ) -> None:
        """Starts ``floe`` (a path, or a name on PATH) and waits until it listens.

        Raises RuntimeError with the server's log if it exits first or takes longer than
        ``timeout`` seconds (e.g. ``backend="gpu"`` where no GPU adapter exists).
        """
        _check_binary(floe)
        # Output goes to files rather than pipes: a pipe nobody reads would block the server.
        self._out = tempfile.TemporaryFile(mode="w+")
        self._log = tempfile.TemporaryFile(mode="w+")
        cmd = [os.fspath(floe), "serve", "--grpc", "127.0.0.1:0", "--http", "127.0.0.1:0", "--scene", "none"]
        self._data = tempfile.TemporaryDirectory(prefix="floe-") if data_dir is None else None
        data = os.fspath(data_dir) if data_dir is not None else self._data.name
        cmd += ["--backend", backend, "--data-dir", data, *args]
        env = {**os.environ, "FLOE_LOG": "info"}
        self._process = subprocess.Popen(cmd, stdout=self._out, stderr=self._log, stdin=subprocess.DEVNULL, env=env)
        try:
            self.http = self._wait_ready(timeout)
            grpc = _GRPC_LINE.search(self.log())
            if grpc is None:
                raise RuntimeError(f"floe serve did not log its gRPC address:\n{self.log()}")
            self.address = f"http://{grpc.group(1)}"
        except BaseException:
            self.stop()
            raise

    def _wait_ready(self, timeout: float) -> str:
        # `floe serve` prints the viewer's URL once it listens (after logging both addresses).
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            for line in _read(self._out).splitlines():
                m = _READY_LINE.search(line)
                if m:
                    return m.group(1)
            if self._process.poll() is not None:
                raise RuntimeError(f"floe serve exited with {self._process.returncode}:\n{self.log()}")
            time.sleep(0.05)
        raise RuntimeError(f"floe serve did not listen within {timeout} s:\n{self.log()}")

    def connect(self, *, token: str | None = None) -> Client:
        """A client of this server whose scenes know their ``viewer_url``."""
        return connect(self.address, token=token, viewer=self.http)

    def log(self) -> str:
        """What the server logged so far."""
        return _read(self._log)

    def stop(self) -> None:
        """Stops the server (SIGTERM: scenes are checkpointed, streams end) and waits for it."""
        if self._process.poll() is None:
            self._process.terminate()
            try:
                self._process.wait(timeout=30)
            except subprocess.TimeoutExpired:
                self._process.kill()
                self._process.wait()
        self._out.close()
        self._log.close()
        if self._data is not None:
            self._data.cleanup()

    def __enter__(self) -> Server:
        return self

    def __exit__(self, *exc: object) -> None:
        self.stop()


def _read(f: IO[str]) -> str:
    f.seek(0)
    return f.read()


def _check_binary(floe: str | os.PathLike[str]) -> None:
    """Refuses a ``floe`` that names no program, saying where it looked (a relative path is
    the current directory's: ``target/release/floe`` exists only from the repository's root)."""
    name = os.fspath(floe)
    if os.sep in name or (os.altsep is not None and os.altsep in name):
        if not os.path.isfile(name):
            raise FileNotFoundError(
                f"no floe binary at {name!r} (looked at {os.path.abspath(name)!r}): build it with "
                "`cargo build --release -p floe-server` and give its path from here, or an absolute path"
            )
    elif shutil.which(name) is None:
        raise FileNotFoundError(
            f"no {name!r} on PATH: give the binary's path, e.g. Server('/path/to/floe/target/release/floe')"
        )
