"""Regions of interest and particle budgets: what part of a scene a frame stream carries.

The server culls and thins before it encodes, so a view of a large scene costs bytes and
encode time in proportion to what it keeps. Without a camera a budget keeps a uniform
random subset of the region; with one, every particle near the camera and a share falling
as 1 / distance^2 farther out, the same particles from frame to frame. Identity-ordered
frames then carry the ids of the particles they hold (``Frame.ids``). Units are SI.

    view = View(box=((0, 0, 0), (1, 1, 1)), budget=100_000)
    with floe.frames(scene, view=view) as frames: ...
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from ._proto import scenes_pb2 as pb


@dataclass(frozen=True)
class Camera:
    """A camera: its position (m), the direction it looks in, the full opening angle of the
    cone it sees (degrees; a viewer passes its diagonal field of view) and the farthest it
    sees (m; None: no limit)."""

    position: Sequence[float]
    direction: Sequence[float]
    fov_deg: float = 90.0
    far: float | None = None


@dataclass(frozen=True)
class View:
    """A region (a box ``(min, max)`` in m, a camera, or both) and the most particles per
    frame (None: every particle in the region)."""

    box: tuple[Sequence[float], Sequence[float]] | None = None
    camera: Camera | None = None
    budget: int | None = None

    def to_message(self) -> pb.FrameView:
        """The view as its gRPC message."""
        m = pb.FrameView(budget=self.budget or 0)
        if self.box is not None:
            m.box.min.extend(float(x) for x in self.box[0])
            m.box.max.extend(float(x) for x in self.box[1])
        if self.camera is not None:
            c = self.camera
            m.camera.position.extend(float(x) for x in c.position)
            m.camera.direction.extend(float(x) for x in c.direction)
            m.camera.fov_deg = float(c.fov_deg)
            m.camera.far = float(c.far or 0.0)
        return m
