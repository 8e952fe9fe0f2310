"""Against a real lab server (users with tokens): each user sees only their own scenes, a
call without a token is refused as unauthenticated, and the token travels with streams."""

from __future__ import annotations

import re
import subprocess
from collections.abc import Iterator
from pathlib import Path

import pytest
from conftest import FLOE, SMALL

import floe_client


def add_user(data: Path, name: str) -> str:
    """`floe admin user add NAME` on the server's data directory; returns the printed token."""
    out = subprocess.run(
        [FLOE, "admin", "--data-dir", data, "user", "add", name], check=True, capture_output=True, text=True
    ).stdout
    token = re.search(r"floe_pat_\w+", out)
    assert token, out
    return token.group(0)


@pytest.fixture(scope="module")
def lab(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[floe_client.local.Server, str, str]]:
    data = tmp_path_factory.mktemp("lab")
    ada, bob = add_user(data, "ada"), add_user(data, "bob")
    with floe_client.local.Server(FLOE, backend="cpu", data_dir=data) as server:
        yield server, ada, bob


def test_users_see_only_their_own_scenes(lab: tuple[floe_client.local.Server, str, str]) -> None:
    server, ada, bob = lab
    with floe_client.connect(server.address, token=ada) as a, floe_client.connect(server.address, token=bob) as b:
        scene = a.create_preset("dam_break", SMALL)
        assert [s.scene_id for s in a.list()] == [scene.scene_id]
        assert b.list() == []
        with pytest.raises(floe_client.NotFound):
            b.get(scene.scene_id)
        with pytest.raises(floe_client.NotFound):
            b.step(scene.scene_id, steps=1)
        a.step(scene.scene_id, steps=2)
        with a.frames(scene.scene_id) as frames:
            assert next(frames).header.step == 2
        a.delete(scene.scene_id)


def test_a_call_without_a_token_is_unauthenticated(lab: tuple[floe_client.local.Server, str, str]) -> None:
    server, _, _ = lab
    with floe_client.connect(server.address) as anonymous, pytest.raises(floe_client.Unauthenticated):
        anonymous.list()
    with floe_client.connect(server.address, token="floe_pat_" + "0" * 64) as wrong:
        with pytest.raises(floe_client.Unauthenticated) as e:
            wrong.list()
        assert isinstance(e.value, PermissionError)
