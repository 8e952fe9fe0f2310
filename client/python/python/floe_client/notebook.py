"""Floe in a Jupyter or VS Code notebook.

- :meth:`Client.show <floe_client.Client.show>` puts the live browser viewer in the cell's
  output, on a read-only share link: the cell watches the scene and cannot steer it.
- :func:`plot_frame` (``Frame.plot``) draws a still picture of a frame with matplotlib,
  coloured by any channel, for notebooks exported to HTML or run headless.
- :func:`track` steps a scene and records what its scheme and modules measure (energies,
  errors, solver iterations) and the real-time factor, every ``every`` simulated seconds;
  :meth:`Track.plot` draws them over time, one panel a measure, with its unit.

The viewer is shown in an IFrame (``IPython.display.IFrame``) rather than a widget: it is
already a complete page the server serves, it draws frames straight from the server's
WebSocket (not through the kernel), and an IFrame renders the same in Jupyter, JupyterLab,
VS Code and exported HTML. A widget (anywidget) would need a second copy of the viewer in
a bundle and would carry every frame through the kernel's comm channel.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    import pandas

    from .client import Client, SceneLike
    from .frames import Frame

#: Axes of each projection (Floe's y is up).
_PROJECTIONS = {"xy": (0, 1), "xz": (0, 2), "zy": (2, 1)}


def _require(module: str, extra: str) -> Any:
    """Imports ``module``, or raises ImportError naming the extra that installs it."""
    import importlib

    try:
        return importlib.import_module(module)
    except ModuleNotFoundError:
        raise ModuleNotFoundError(
            f"{module} is needed for this; install it with pip install 'floe-client[{extra}]'"
        ) from None


def share_url(client: Client, scene: SceneLike) -> str:
    """A new read-only share link of ``scene`` as the viewer's URL (``<viewer>/#scene=ID&token=...``,
    as the REST API's share call gives it).

    Raises ValueError when the client does not know the viewer's address.
    """
    if not client.viewer:
        raise ValueError(
            "the client does not know the server's viewer address: connect with "
            "floe_client.connect(address, viewer='http://host:8080') or floe_client.local.Server(...).connect()"
        )
    link = client.share(scene)
    return f"{client.viewer}/#scene={link.scene_id}&token={link.token}"


def show(client: Client, scene: SceneLike, *, width: str | int = "100%", height: int = 480) -> Any:
    """The live viewer of ``scene`` as a notebook display object (an ``IPython.display.IFrame``),
    on a new read-only share link; the last expression of a cell displays it."""
    display = _require("IPython.display", "notebook")
    return display.IFrame(share_url(client, scene), width=width, height=height)


def plot_frame(
    frame: Frame,
    channel: str | None = None,
    *,
    projection: str = "xy",
    ax: Any = None,
    cmap: str = "viridis",
    size: float = 2.0,
) -> Any:
    """Draws ``frame``'s particles projected on a plane, coloured by ``channel``.

    Args:
        channel: a channel of the frame (a vector channel is drawn by its magnitude); None
            draws every particle in one colour.
        projection: "xy" (side view: x across, y up), "xz" (from above) or "zy".
        ax: matplotlib axes to draw on; a new figure's when None.
        cmap: matplotlib colour map.
        size: marker area (points squared).

    Returns the axes.
    """
    plt = _require("matplotlib.pyplot", "plot")
    if projection not in _PROJECTIONS:
        raise ValueError(f"projection must be one of {', '.join(_PROJECTIONS)}, got {projection!r}")
    a, b = _PROJECTIONS[projection]
    if ax is None:
        _, ax = plt.subplots(figsize=(6, 4.5))
    p = frame.positions
    colour = None
    if channel is not None:
        values = np.asarray(frame[channel], dtype=np.float64)
        colour = np.linalg.norm(values, axis=1) if values.ndim == 2 else values
    drawn = ax.scatter(p[:, a], p[:, b], c=colour, s=size, cmap=cmap if colour is not None else None, linewidths=0)
    if colour is not None:
        unit = frame.channels[channel].unit
        label = f"|{channel}|" if values.ndim == 2 else channel
        ax.figure.colorbar(drawn, ax=ax, label=f"{label} ({unit})" if unit else label)
    names = "xyz"
    ax.set_xlabel(f"{names[a]} (m)")
    ax.set_ylabel(f"{names[b]} (m)")
    ax.set_aspect("equal")
    ax.set_title(f"t = {frame.header.time:.3f} s, {len(p):,} particles")
    return ax


@dataclass(frozen=True)
class Track:
    """A scene's measures over simulated time (:func:`track`)."""

    #: One row per sample, indexed by ``sim_time`` (s): ``steps``, ``dt`` (the last step, s),
    #: ``real_time_factor`` (simulated seconds per wall second over the interval before the
    #: sample) and every measure by name.
    table: pandas.DataFrame
    #: Each column's unit ("" when dimensionless).
    units: dict[str, str]

    def plot(self, *names: str, axes: Any = None) -> Any:
        """Draws the named columns (every measure and the real-time factor when none are
        named) against simulated time, one panel each. Returns the axes."""
        plt = _require("matplotlib.pyplot", "plot")
        names = names or tuple(c for c in self.table.columns if c not in ("steps", "dt"))
        missing = [n for n in names if n not in self.table.columns]
        if missing:
            raise KeyError(f"no column {', '.join(map(repr, missing))}; the track has {', '.join(self.table.columns)}")
        if axes is None:
            _, axes = plt.subplots(len(names), 1, sharex=True, figsize=(6, 1.8 * len(names) + 0.6), squeeze=False)
            axes = axes[:, 0]
        for ax, name in zip(axes, names, strict=True):
            ax.plot(self.table.index, self.table[name])
            unit = self.units.get(name, "")
            ax.set_ylabel(f"{name}\n({unit})" if unit else name, fontsize=8)
        axes[-1].set_xlabel("simulated time (s)")
        return axes


def track(client: Client, scene: SceneLike, until: float, every: float) -> Track:
    """Steps the paused ``scene`` to simulated time ``until`` (s), sampling its measures and the
    real-time factor every ``every`` simulated seconds. Needs pandas (the ``pandas`` extra)."""
    pandas = _require("pandas", "pandas")
    if not every > 0:
        raise ValueError(f"every must be a positive time in seconds, got {every}")
    rows: list[dict[str, float]] = []
    units = {"real_time_factor": "", "steps": "", "dt": "s"}
    start = t = client.get(scene).sim_time
    # Samples at the first step at or after each multiple of `every` from the start.
    targets = (min(start + k * every, until) for k in range(1, int((until - start) / every) + 2))
    for target in targets:
        if target <= t:
            continue
        wall = time.perf_counter()
        info = client.step(scene, until=target)
        wall = time.perf_counter() - wall
        stats = client.stats(scene)
        row = {
            "sim_time": info.sim_time,
            "steps": info.steps,
            "dt": stats.dt,
            "real_time_factor": (info.sim_time - t) / wall,
        }
        for m in stats.measures.values():
            row[m.name] = m.value
            units[m.name] = m.unit
        rows.append(row)
        if info.state != "paused" or info.sim_time <= t or info.sim_time >= until:
            break
        t = info.sim_time
    return Track(pandas.DataFrame(rows).set_index("sim_time"), units)
