"""Decoding speed in Python: frames of a ~110k-particle dam break, recorded live from a server
in both modes, decoded by ``floe_client.Decoder`` (floe-proto through the extension module,
into numpy arrays) on one thread.

    python client/python/scripts/bench_decode.py [--floe target/release/floe]

Prints a Markdown table: mode, channels, frames, bytes per particle, M particles/s (best of
20 passes over the frames; each pass decodes every frame with a fresh decoder, as a client
joining the stream would). Build the package in release mode (``pip install ./client/python``,
the default) and the server too: ``cargo build --release -p floe-server``.
"""

from __future__ import annotations

import argparse
import pathlib
import threading
import time

import floe_client

ROOT = pathlib.Path(__file__).resolve().parents[3]


def record(client: floe_client.Client, scene: floe_client.SceneInfo, count: int, **options) -> list[bytes]:
    """``count`` consecutive encoded frames of a stream with ``options``, from its first (a keyframe)."""
    with client.frames(scene, **options) as frames:
        return [frames.next_raw() for _ in range(count)]


def best_rate(frames: list[bytes], passes: int) -> float:
    """Particles decoded per second, best of ``passes`` passes."""
    particles = sum(int.from_bytes(f[12:16], "little") for f in frames)
    best = float("inf")
    for _ in range(passes):
        decoder = floe_client.Decoder()
        start = time.perf_counter()
        for data in frames:
            decoder.decode(data)
        best = min(best, time.perf_counter() - start)
    return particles / best


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--floe", default=ROOT / "target" / "release" / "floe", help="floe binary to start")
    parser.add_argument("--spacing", type=float, default=0.5 / 48, help="spacing (m); a/48: 110,592 particles")
    parser.add_argument("--until", type=float, default=0.05, help="simulated time (s) to step before recording")
    parser.add_argument("--frames", type=int, default=30, help="frames recorded per stream")
    parser.add_argument("--passes", type=int, default=20, help="passes over the frames; the best counts")
    args = parser.parse_args()

    with floe_client.local.Server(args.floe, backend="cpu") as server, floe_client.connect(server.address) as client:
        scene = client.create_preset("dam_break", {"particle_spacing": args.spacing})
        start = client.step(scene, until=args.until)
        streams = {
            ("identity", "positions"): {"mode": "identity"},
            ("unordered", "positions"): {"mode": "unordered"},
            ("identity", "+ velocity, density, pressure"): {
                "mode": "identity",
                "channels": ["velocity", "density", "pressure"],
            },
        }
        recorded: dict = {}

        def take(key, options) -> None:
            recorded[key] = record(client, scene, args.frames, fps=240, **options)

        threads = [threading.Thread(target=take, args=item) for item in streams.items()]
        for t in threads:
            t.start()
        client.run(scene)
        for t in threads:
            t.join()
        info = client.pause(scene)

    print(f"dam break, {scene.particles:,} particles, frames from t = {start.sim_time:.3f} s to {info.sim_time:.3f} s")
    print(f"(steps {start.steps} to {info.steps}); best of {args.passes} passes on one thread\n")
    print("| mode | channels | frames | bytes/particle | decode M particles/s |")
    print("|---|---|---:|---:|---:|")
    for mode, channels in streams:
        frames = recorded[(mode, channels)]
        size = sum(len(f) for f in frames) / (len(frames) * scene.particles)
        rate = best_rate(frames, args.passes) / 1e6
        print(f"| {mode} | {channels} | {len(frames)} | {size:.2f} | {rate:.0f} |")


if __name__ == "__main__":
    main()
