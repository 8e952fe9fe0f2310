"""The dam break's surge front from identity-ordered frames, against the experiment of
Koshizuka & Oka (1996), Nucl. Sci. Eng. 123, 421-434, plotted with matplotlib.

    pip install './client/python[plot]'
    python client/python/examples/dam_break_surge_front.py --out surge_front.png

Starts a private server (``--floe``, default target/release/floe) unless ``--server`` names
one. Dimensionless time ``T = t sqrt(2 g / a)`` and front ``Z = x_front / a``, with a = 0.5 m
the column's width and ``x_front`` the largest particle x plus half a spacing, measured from
the wall the column rests against, as ``floe validate`` measures it. The reference points are
the engine's copy, server/engine/data/dam_break_surge_front.csv (digitised in the public PySPH
examples).
"""

from __future__ import annotations

import argparse
import csv
import math
import pathlib

import numpy as np

import floe_client

ROOT = pathlib.Path(__file__).resolve().parents[3]
REFERENCE = ROOT / "server" / "engine" / "data" / "dam_break_surge_front.csv"
SERIES = "koshizuka_oka_1996_experiment"


def reference(series: str = SERIES) -> list[tuple[float, float]]:
    """(T, Z) points of one series of the reference file."""
    with open(REFERENCE) as f:
        rows = csv.DictReader(line for line in f if not line.startswith("#"))
        return [(float(r["T"]), float(r["Z"])) for r in rows if r["series"] == series]


def surge_front(client: floe_client.Client, overrides: dict, t_end: float = 3.1) -> list[tuple[float, float]]:
    """Runs a dam break (preset plus ``overrides``) until dimensionless time ``t_end`` and
    returns (T, Z) from every frame received."""
    scene = client.create_preset("dam_break", overrides)
    try:
        doc = scene.scene
        block = doc["fluids"][0]["blocks"][0]
        a = block["max"][0] - block["min"][0]
        wall_x = block["min"][0]
        g = -doc["gravity"][1]
        half = 0.5 * doc["particle_spacing"]
        t_scale = math.sqrt(2 * g / a)
        history = []
        with client.frames(scene, fps=240) as frames:
            client.run(scene)
            for frame in frames:
                x_front = float(frame.positions[:, 0].max())
                history.append((frame.header.time * t_scale, (x_front + half - wall_x) / a))
                if history[-1][0] >= t_end:
                    break
        return history
    finally:
        client.delete(scene)


def error(history: list[tuple[float, float]], points: list[tuple[float, float]], t_max: float = 3.0) -> float:
    """Root mean square of simulated minus reference Z over reference points with T <= t_max."""
    t, z = np.array(history).T
    ref = np.array([p for p in points if p[0] <= t_max])
    return float(np.sqrt(np.mean((np.interp(ref[:, 0], t, z) - ref[:, 1]) ** 2)))


def plot(history: list[tuple[float, float]], points: list[tuple[float, float]], label: str, out: pathlib.Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 4.5))
    ax.plot(*np.array(history).T, label=f"Floe ({label})")
    ax.plot(*np.array(points).T, "o", label="Koshizuka & Oka (1996), experiment")
    ax.set_xlabel(r"$T = t\,\sqrt{2g/a}$")
    ax.set_ylabel(r"$Z = x_{front}/a$")
    ax.set_title("Dam break surge front")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(out, dpi=120)


def main() -> None:
    parser = argparse.ArgumentParser(description="Dam break surge front against Koshizuka & Oka (1996).")
    parser.add_argument("--server", help="address of a running server (default: start --floe)")
    parser.add_argument("--floe", default=ROOT / "target" / "release" / "floe", help="floe binary to start")
    parser.add_argument("--backend", default="auto", help="backend of the started server: auto, gpu, cpu")
    parser.add_argument("--spacing", type=float, default=0.5 / 28, help="particle spacing (m); a/28 by default")
    parser.add_argument("--out", type=pathlib.Path, default=pathlib.Path("surge_front.png"))
    args = parser.parse_args()

    overrides = {"particle_spacing": args.spacing}
    if args.server:
        with floe_client.connect(args.server) as client:
            history = surge_front(client, overrides)
    else:
        with floe_client.local.Server(args.floe, backend=args.backend) as server:
            with floe_client.connect(server.address) as client:
                history = surge_front(client, overrides)
    points = reference()
    rms = error(history, points)
    print(f"{len(history)} frames to T = {history[-1][0]:.2f}; front Z = {history[-1][1]:.2f}")
    print(f"RMS error against Koshizuka & Oka for T <= 3: {rms:.3f}")
    plot(history, points, f"spacing {args.spacing * 1000:.1f} mm", args.out)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
