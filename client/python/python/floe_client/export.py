"""Frames for notebooks and post-processing: a pandas DataFrame, or a legacy VTK file that
ParaView reads. Neither needs more than numpy to import; ``to_dataframe`` needs pandas
(``pip install 'floe-client[pandas]'``).
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import pandas

    from .frames import Frame

_AXES = ("x", "y", "z", "w")


def columns(frame: Frame) -> dict[str, tuple[np.ndarray, str]]:
    """Each column of the frame's table with its unit: ``x, y, z`` (m), then per channel
    ``name`` for one component or ``name_x, name_y, ...`` for several (as ``floectl export``
    names the columns of a CSV)."""
    out: dict[str, tuple[np.ndarray, str]] = {}
    for ch in frame.channels.values():
        if ch.name == "ids":
            continue
        if ch.values.ndim == 1:
            out[ch.name] = (ch.values, ch.unit)
            continue
        for k, axis in zip(range(ch.values.shape[1]), _AXES):
            name = axis if ch.name == "position" else f"{ch.name}_{axis}"
            out[name] = (ch.values[:, k], ch.unit)
    return out


def to_dataframe(frame: Frame) -> pandas.DataFrame:
    """One row per particle, one column per component (see :func:`columns`); units in
    ``df.attrs["units"]``, the header in ``df.attrs["header"]``. Identity-ordered frames
    are indexed by particle id: the frame's ids where it carries them (``Frame.ids``: a
    part such as the solid's particles), else the row (with decimation n, id ``i * n`` is
    not known to the frame, so the index is the row). Needs pandas (the ``[pandas]`` extra)."""
    try:
        import pandas
    except ImportError as e:
        raise ModuleNotFoundError(
            "to_dataframe needs pandas, which is not installed: pip install 'floe-client[pandas]' "
            "(or './client/python[pandas]' from Floe's repository)",
            name="pandas",
        ) from e

    cols = columns(frame)
    df = pandas.DataFrame({name: values for name, (values, _) in cols.items()})
    if frame.ids is not None:
        df.index = pandas.Index(frame.ids, name="id")
    elif frame.header.mode == "identity":
        df.index.name = "id"
    df.attrs["units"] = {name: unit for name, (_, unit) in cols.items()}
    df.attrs["header"] = frame.header
    return df


def write_vtk(frame: Frame, path: str | os.PathLike[str]) -> None:
    """Writes the frame as legacy VTK (version 3.0) binary polydata, the layout of
    ``floe run --export`` and ``floectl export``: one vertex per particle, ``id`` (identity
    frames only; the frame's ids where it carries them) and every channel as point data
    (three components as VECTORS, others as SCALARS, exact channels as unsigned_char); the
    set and the time in the title."""
    n = frame.header.particle_count
    be_f32 = np.dtype(">f4")
    be_u32 = np.dtype(">u4")
    with open(path, "wb") as out:
        out.write(b"# vtk DataFile Version 3.0\n")
        out.write(f"floe {frame.header.particle_set or 'particles'} t={frame.header.time:.6f} s\n".encode())
        out.write(f"BINARY\nDATASET POLYDATA\nPOINTS {n} float\n".encode())
        out.write(frame.positions.astype(be_f32).tobytes() + b"\n")
        out.write(f"VERTICES {n} {2 * n}\n".encode())
        vertices = np.empty((n, 2), be_u32)
        vertices[:, 0] = 1
        vertices[:, 1] = np.arange(n)
        out.write(vertices.tobytes() + b"\n")
        out.write(f"POINT_DATA {n}\n".encode())
        if frame.header.mode == "identity":
            ids = frame.ids if frame.ids is not None else np.arange(n)
            out.write(b"SCALARS id int 1\nLOOKUP_TABLE default\n")
            out.write(ids.astype(">i4").tobytes() + b"\n")
        for ch in frame.channels.values():
            if ch.name in ("position", "ids"):
                continue
            name = ch.name.replace(" ", "_")
            if ch.values.dtype == np.uint8:
                out.write(f"SCALARS {name} unsigned_char 1\nLOOKUP_TABLE default\n".encode())
                out.write(ch.values.tobytes() + b"\n")
                continue
            components = 1 if ch.values.ndim == 1 else ch.values.shape[1]
            if components == 3:
                out.write(f"VECTORS {name} float\n".encode())
            else:
                out.write(f"SCALARS {name} float {components}\nLOOKUP_TABLE default\n".encode())
            out.write(ch.values.astype(be_f32).tobytes() + b"\n")
