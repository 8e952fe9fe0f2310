"""A view of a large scene through the Python client: a dam break of about 4M particles on
the CPU (a private ``floe serve``), its frames whole and through views holding a share of it
(a box, a budget alone, a camera with a budget), received and decoded by ``floe_client``.

    python client/python/scripts/bench_view.py [--floe target/release/floe] [--particles 4000000] [--share 0.05]

Prints a Markdown table per mode: the view, particles and bytes per frame, the time from
opening the stream to the first frame received (the server reads the scene, culls, encodes
and sends it), and the time to decode it in Python; best of ``--repeat`` streams each, the
scene paused so every frame is of the same state. Build the server in release mode first
(``cargo build --release -p floe-server``) and install the package (``pip install ./client/python``).
"""

from __future__ import annotations

import argparse
import pathlib
import time

import numpy as np

import floe_client
from floe_client import Camera, View

ROOT = pathlib.Path(__file__).resolve().parents[3]


def first_frame(client: floe_client.Client, scene: floe_client.SceneInfo, mode: str, view: View | None):
    """Seconds to the first frame, its bytes, seconds to decode it, and the decoded frame."""
    start = time.perf_counter()
    with client.frames(scene, mode=mode, view=view, channels=["velocity"]) as frames:
        raw = frames.next_raw()
    received = time.perf_counter() - start
    decoder = floe_client.Decoder()
    start = time.perf_counter()
    frame = decoder.decode(raw)
    return received, len(raw), time.perf_counter() - start, frame


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--floe", default=str(ROOT / "target" / "release" / "floe"))
    parser.add_argument("--particles", type=int, default=4_000_000)
    parser.add_argument("--share", type=float, default=0.05)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()

    with floe_client.local.Server(args.floe, backend="cpu", timeout=300) as server:
        client = server.connect()
        spacing = 0.5 / round(args.particles ** (1 / 3))
        scene = client.create_preset("dam_break", {"particle_spacing": spacing})
        client.step(scene, 1)
        n = scene.particles
        _, _, _, whole = first_frame(client, scene, "unordered", None)
        x = np.sort(whole.positions[:, 0])
        k = int(n * args.share)
        cut = float(x[k])
        lo, hi = whole.positions.min(axis=0), whole.positions.max(axis=0)
        centre = (lo + hi) / 2
        camera = Camera(
            position=(float(centre[0]), float(centre[1]), float(centre[2] + 2 * (hi[0] - lo[0]))),
            direction=(0.0, 0.0, -1.0),
            fov_deg=90.0,
        )
        views = [
            ("whole scene", None),
            (f"box, x below {cut:.3f} m", View(box=((-1.0, -1.0, -1.0), (cut, 10.0, 10.0)))),
            (f"budget {k}", View(budget=k)),
            (f"camera, budget {k}", View(camera=camera, budget=k)),
        ]
        print(
            f"dam break, {n} particles with velocities after one step, CPU backend; views holding "
            f"{100 * args.share:.0f} %; best of {args.repeat} streams each"
        )
        print("| mode | view | particles | bytes/frame | first frame ms | decode ms | bytes: whole / view |")
        print("|---|---|---:|---:|---:|---:|---:|")
        for mode in ("unordered", "identity"):
            whole_bytes = None
            for label, view in views:
                runs = [first_frame(client, scene, mode, view) for _ in range(args.repeat)]
                received = min(r[0] for r in runs)
                decoded = min(r[2] for r in runs)
                size, frame = runs[0][1], runs[0][3]
                whole_bytes = whole_bytes or size
                print(
                    f"| {mode} | {label} | {len(frame.positions)} | {size} | {1e3 * received:.0f} | "
                    f"{1e3 * decoded:.1f} | {whole_bytes / size:.1f} |"
                )


if __name__ == "__main__":
    main()
