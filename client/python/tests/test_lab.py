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


def test_show_displays_the_live_viewer_on_a_read_only_share_link(
    lab: tuple[floe_client.local.Server, str, str],
) -> None:
    import urllib.error
    import urllib.parse
    import urllib.request

    from IPython.display import IFrame

    server, ada, _ = lab
    with server.connect(token=ada) as a:
        scene = a.create_preset("dam_break", SMALL)
        shown = a.show(scene, height=400)
        assert isinstance(shown, IFrame) and shown.height == 400
        page, fragment = shown.src.split("/#")
        assert page == server.http
        params = urllib.parse.parse_qs(fragment)
        assert params["scene"] == [str(scene.scene_id)]
        token = params["token"][0]
        assert token != ada
        assert "<iframe" in shown._repr_html_() and token in shown._repr_html_()

        def call(method: str, path: str, body: bytes | None = None) -> int:
            request = urllib.request.Request(
                f"{page}{path}",
                data=body,
                method=method,
                headers={"authorization": f"Bearer {token}", "content-type": "application/json"},
            )
            try:
                with urllib.request.urlopen(request) as r:
                    return r.status
            except urllib.error.HTTPError as e:
                return e.code

        # The link watches the scene (the viewer's page, the scene, its frames' socket)...
        with urllib.request.urlopen(page + "/") as r:
            assert r.status == 200 and b"<canvas" in r.read()
        assert call("GET", f"/api/v1/scenes/{scene.scene_id}") == 200
        # ...and cannot steer it, over REST or gRPC.
        assert call("POST", f"/api/v1/scenes/{scene.scene_id}/step", b'{"steps": 1}') == 403
        with floe_client.connect(server.address, token=token) as watcher:
            assert watcher.get(scene).steps == 0
            with pytest.raises(floe_client.PermissionDenied):
                watcher.step(scene, steps=1)
        a.delete(scene)
