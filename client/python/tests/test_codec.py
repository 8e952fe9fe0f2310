"""The extension module against floe-proto's golden frames (no server): every header field
and every decoded value equal to the Rust decoder's, in the dtypes and shapes promised."""

from __future__ import annotations

import json

import numpy as np
import pytest

import floe_client
from conftest import GOLDEN

# The unit the package gives each channel (proto/channels.json); per-scene channels have none.
UNITS = {"position": "m", "velocity": "m/s", "density": "kg/m^3", "pressure": "Pa", "temperature": "K", "material": ""}
MODES = {"identity_ordered": "identity", "unordered": "unordered", "grid": "grid"}
CURRENT = ["unordered_positions", "unordered_channels", "identity_keyframe", "identity_delta", "identity_linear"]
NAMES = CURRENT + ["grid_field"] + [f"v3/{n}" for n in CURRENT]


def load(name: str) -> tuple[bytes, dict]:
    return (GOLDEN / f"{name}.bin").read_bytes(), json.loads((GOLDEN / f"{name}.json").read_text())


@pytest.mark.parametrize("name", NAMES)
def test_golden_frames_decode_to_the_sidecar_values(name: str) -> None:
    data, sidecar = load(name)
    folder = name.rpartition("/")[0]
    decoder = floe_client.Decoder()
    for before in sidecar["decode_after"]:
        decoder.decode(load(f"{folder}/{before.removesuffix('.bin')}".lstrip("/"))[0])
    frame = decoder.decode(data)

    h, expected = frame.header, sidecar["header"]
    assert (h.scene_id, h.sequence, h.base_sequence, h.step) == tuple(
        expected[k] for k in ("scene_id", "sequence", "base_sequence", "step")
    )
    assert h.time == expected["time"]
    assert (h.keyframe, h.particle_count, h.frame_len, h.version) == (
        expected["keyframe"],
        expected["particle_count"],
        expected["frame_len"],
        expected["version"],
    )
    assert h.mode == MODES[expected["mode"]]
    assert (h.set, h.particle_set) == (expected["set"], None)

    kinds = [c["kind"] for c in expected["channels"] if c["kind"] != "grid"]
    assert list(frame.channels) == kinds
    n = h.particle_count
    if h.mode == "grid":
        grid = sidecar["grid"]
        assert h.grid == (tuple(grid["origin"]), tuple(np.float32(s) for s in grid["size"]), tuple(grid["dims"]))
    for info in expected["channels"]:
        if info["kind"] == "grid":
            continue
        ch = frame.channels[info["kind"]]
        assert ch.unit == UNITS.get(ch.name, "") and ch.tag == info["tag"]
        assert ch.max_error == tuple(np.float32(r["max_error"]) for r in info["ranges"])
        dtype = np.uint8 if ch.name == "material" else np.float32
        c = info["components"]
        shape = (n, c) if c > 1 else (n,)
        assert ch.values.dtype == dtype and ch.values.shape == shape
        want = sidecar["positions"] if ch.name == "position" else sidecar["channels"][ch.name]
        np.testing.assert_array_equal(ch.values, np.array(want, dtype=dtype))
    if h.mode != "grid":
        assert frame.positions is frame.channels["position"].values
    assert decoder.last_sequence == h.sequence


def test_arrays_take_over_the_decoders_buffers() -> None:
    frame = floe_client.Decoder().decode(load("unordered_channels")[0])
    for ch in frame.channels.values():
        assert ch.values.flags.c_contiguous and not ch.values.flags.owndata
        # (N, 3) arrays are views of the flat (3N,) array that holds the Rust allocation.
        owner = ch.values.base if ch.values.ndim == 1 else ch.values.base.base
        assert not isinstance(owner, np.ndarray), f"{ch.name}: data owned by numpy, so it was copied"


def test_bad_frames_raise_decode_error_and_leave_the_decoder_as_it_was() -> None:
    keyframe, _ = load("identity_keyframe")
    delta, _ = load("identity_delta")
    decoder = floe_client.Decoder()
    with pytest.raises(floe_client.DecodeError, match="keyframe is needed"):
        decoder.decode(delta)
    with pytest.raises(floe_client.DecodeError, match="bad magic"):
        decoder.decode(b"nope" + keyframe[4:])
    with pytest.raises(floe_client.DecodeError, match="incomplete"):
        decoder.decode(keyframe[:100])
    assert isinstance(floe_client.DecodeError("x"), ValueError)

    decoder.decode(keyframe)
    corrupt = bytearray(delta)
    corrupt[-40:] = bytes(40)
    with pytest.raises(floe_client.DecodeError):
        decoder.decode(bytes(corrupt))
    assert decoder.held_sequence == 0
    assert decoder.decode(delta).header.sequence == 1
    decoder.reset()
    assert decoder.held_sequence is None


def test_limits_refuse_large_frames() -> None:
    with pytest.raises(floe_client.DecodeError, match="over the limit of 100"):
        floe_client.Decoder(max_particles=100).decode(load("unordered_positions")[0])
    with pytest.raises(floe_client.DecodeError, match="over the limit of 1000"):
        floe_client.Decoder(max_frame_bytes=1000).decode(load("unordered_positions")[0])


def test_frame_item_access_names_what_is_there() -> None:
    frame = floe_client.Decoder().decode(load("identity_keyframe")[0])
    assert frame["velocity"] is frame.channels["velocity"].values
    with pytest.raises(KeyError, match="position, velocity, material"):
        frame["density"]
