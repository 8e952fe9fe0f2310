"""The examples' code against the test server, at coarse resolutions."""

from __future__ import annotations

import importlib.util
import pathlib
import types

import numpy as np

import floe_client
from conftest import ROOT, SMALL

EXAMPLES = ROOT / "client" / "python" / "examples"


def example(name: str) -> types.ModuleType:
    spec = importlib.util.spec_from_file_location(name, EXAMPLES / f"{name}.py")
    assert spec and spec.loader
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_surge_front_starts_at_the_column_and_advances(client: floe_client.Client, tmp_path: pathlib.Path) -> None:
    surge = example("dam_break_surge_front")
    history = surge.surge_front(client, SMALL, t_end=2.0)
    t, z = np.array(history).T
    assert t[0] < 0.1 and abs(z[0] - 1.0) < 0.01, "the front starts at the column's face, Z = 1"
    assert t[-1] >= 2.0 and np.all(np.diff(t) > 0)
    # The front only advances (up to one quantisation step back) and has run a long way by T = 2.
    assert np.all(np.diff(z) > -1e-3) and z[-1] > 1.8
    points = surge.reference()
    assert points[0] == (0.0, 1.0) and len(points) == 9
    assert surge.error(history, points, t_max=2.0) < 0.5
    png = tmp_path / "front.png"
    surge.plot(history, points, "test", png)
    assert png.read_bytes().startswith(b"\x89PNG")


def test_frame_table_compares_pressure_with_hydrostatics(client: floe_client.Client) -> None:
    table_example = example("frame_table")
    frame = table_example.settled_frame(client, 0.05)
    table = table_example.pressure_by_height(frame)
    assert list(table.columns) == ["pressure", "density", "hydrostatic"]
    # Deeper layers carry more pressure, near the hydrostatic value at the bottom.
    assert table["pressure"].is_monotonic_decreasing
    assert abs(table["pressure"].iloc[0] - table["hydrostatic"].iloc[0]) < 0.1 * table["hydrostatic"].iloc[0]
