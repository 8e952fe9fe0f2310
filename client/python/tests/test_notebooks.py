"""The example notebooks (client/python/notebooks/) run headless, as a user runs them, each
starting its own server (the build the tests use), and write their figures; a frame's still
picture and a scene's measures over time, drawn with matplotlib."""

from __future__ import annotations

import pathlib

import nbformat
import pytest
from conftest import FLOE, ROOT, SMALL
from nbclient import NotebookClient

import floe_client

NOTEBOOKS = ROOT / "client" / "python" / "notebooks"
PNG = b"\x89PNG"


@pytest.mark.parametrize(
    ("name", "figures"),
    [
        ("dam_break", ["dam_break_surge_front.png", "dam_break_frame.png", "dam_break_measures.png"]),
        ("ice_bunny", ["bunny_deformation.png", "bunny.png"]),
    ],
)
def test_example_notebook_runs_and_writes_its_figures(
    name: str, figures: list[str], tmp_path: pathlib.Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("FLOE_BIN", str(FLOE))
    monkeypatch.setenv("FLOE_BACKEND", "cpu")
    monkeypatch.setenv("FLOE_NOTEBOOK_OUT", str(tmp_path))
    notebook = nbformat.read(NOTEBOOKS / f"{name}.ipynb", as_version=4)
    NotebookClient(notebook, timeout=600, resources={"metadata": {"path": str(NOTEBOOKS)}}).execute()
    for figure in figures:
        data = (tmp_path / figure).read_bytes()
        assert data.startswith(PNG) and len(data) > 5000, f"{figure}: {len(data)} bytes"
    # The cell that shows the scene displayed the viewer on a share link.
    outputs = [o for c in notebook.cells for o in c.get("outputs", [])]
    html = [o["data"]["text/html"] for o in outputs if "text/html" in o.get("data", {})]
    assert any("<iframe" in h and "/#scene=" in h and "token=" in h for h in html), html


def test_frame_plot_colours_by_a_channel(client: floe_client.Client, tmp_path: pathlib.Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    scene = client.create_preset("dam_break", SMALL)
    client.step(scene, steps=5)
    with client.frames(scene, channels=["velocity", "density"]) as frames:
        frame = next(frames)
    ax = frame.plot("velocity", projection="xz")
    assert ax.get_xlabel() == "x (m)" and ax.get_ylabel() == "z (m)"
    points = ax.collections[0]
    assert len(points.get_offsets()) == frame.header.particle_count
    # Coloured by the speed: the colour bar says so, with the unit.
    assert ax.figure.axes[-1].get_ylabel() == "|velocity| (m/s)"
    assert frame.plot("density").figure.axes[-1].get_ylabel() == "density (kg/m^3)"
    with pytest.raises(ValueError, match="projection must be one of xy, xz, zy"):
        frame.plot(projection="yx")
    with pytest.raises(KeyError, match="no channel 'heat'"):
        frame.plot("heat")
    ax.figure.savefig(tmp_path / "frame.png")
    assert (tmp_path / "frame.png").read_bytes().startswith(PNG)
    client.delete(scene)


def test_track_records_measures_and_real_time_factor(client: floe_client.Client) -> None:
    import matplotlib

    matplotlib.use("Agg")
    scene = client.create_preset("dam_break", SMALL)
    track = floe_client.notebook.track(client, scene, until=0.1, every=0.025)
    table = track.table
    # Each sample at the first step at or after a multiple of 25 ms.
    targets = [0.025, 0.05, 0.075, 0.1]
    assert len(table) == len(targets), table
    for target, (at, dt) in zip(targets, table["dt"].items(), strict=True):
        assert at - dt < target + 1e-6 and at >= target - 1e-6, (target, at, dt)
    assert (table["real_time_factor"] > 0).all()
    assert table["steps"].is_monotonic_increasing
    # Water falling from rest gains kinetic energy.
    assert table["fluid.kinetic_energy"].iloc[-1] > table["fluid.kinetic_energy"].iloc[0] > 0
    assert track.units["fluid.kinetic_energy"] == "J"
    axes = track.plot("fluid.kinetic_energy", "real_time_factor")
    assert [a.get_ylabel() for a in axes] == ["fluid.kinetic_energy\n(J)", "real_time_factor"]
    assert axes[-1].get_xlabel() == "simulated time (s)"
    with pytest.raises(KeyError, match="no column 'energy'"):
        track.plot("energy")
    with pytest.raises(ValueError, match="every must be a positive time"):
        floe_client.notebook.track(client, scene, until=1.0, every=0.0)
    client.delete(scene)


def test_show_needs_the_viewer_address(server: floe_client.local.Server) -> None:
    with floe_client.connect(server.address) as blind:
        scene = blind.create_preset("dam_break", SMALL)
        with pytest.raises(ValueError, match=r"connect\(address, viewer="):
            blind.show(scene)
        blind.delete(scene)
