"""A frame as a pandas table and a VTK file: the hydrostatic tank's pressure against
``rho0 g (H - y)``, as one would explore it in a notebook.

    pip install './client/python[pandas]'
    python client/python/examples/frame_table.py --vtk tank.vtk

Starts a private server (``--floe``, default target/release/floe) unless ``--server`` names one.
"""

from __future__ import annotations

import argparse
import pathlib

import floe_client

ROOT = pathlib.Path(__file__).resolve().parents[3]


def settled_frame(client: floe_client.Client, spacing: float) -> floe_client.Frame:
    """The hydrostatic preset stepped past its damped settling (0.5 s), with densities and pressures."""
    scene = client.create_preset("hydrostatic", {"particle_spacing": spacing})
    try:
        with client.frames(scene, channels=["velocity", "density", "pressure"]) as frames:
            info = client.step(scene, until=0.6)
            return next(f for f in frames if f.header.step == info.steps)
    finally:
        client.delete(scene)


def pressure_by_height(frame: floe_client.Frame, rho0: float = 1000.0, g: float = 9.81, height: float = 0.9):
    """Mean pressure in 10 cm layers next to the hydrostatic ``rho0 g (H - y)`` (Pa)."""
    df = frame.to_dataframe()
    df["layer"] = (df["y"] // 0.1) * 0.1 + 0.05
    table = df.groupby("layer")[["pressure", "density"]].mean()
    table["hydrostatic"] = rho0 * g * (height - table.index)
    return table


def main() -> None:
    parser = argparse.ArgumentParser(description="A hydrostatic tank's frame as a table and a VTK file.")
    parser.add_argument("--server", help="address of a running server (default: start --floe)")
    parser.add_argument("--floe", default=ROOT / "target" / "release" / "floe", help="floe binary to start")
    parser.add_argument("--spacing", type=float, default=0.025, help="particle spacing (m)")
    parser.add_argument("--vtk", type=pathlib.Path, help="also write the frame here (legacy VTK, for ParaView)")
    args = parser.parse_args()

    if args.server:
        with floe_client.connect(args.server) as client:
            frame = settled_frame(client, args.spacing)
    else:
        with floe_client.local.Server(args.floe, backend="cpu") as server, floe_client.connect(server.address) as c:
            frame = settled_frame(c, args.spacing)
    print(f"t = {frame.header.time:.3f} s, {frame.header.particle_count} particles")
    print(frame.to_dataframe().describe().T[["mean", "min", "max"]])
    print(pressure_by_height(frame).round(1))
    if args.vtk:
        frame.write_vtk(args.vtk)
        print(f"wrote {args.vtk}")


if __name__ == "__main__":
    main()
