"""The token given to connect() travels with every call and stream, as the lab server
will read it; checked against an in-process gRPC server that records what it receives."""

from __future__ import annotations

from collections.abc import Iterator
from concurrent import futures

import grpc
import pytest

import floe_client
from floe_client._proto import scenes_pb2 as pb
from floe_client._proto import scenes_pb2_grpc as pb_grpc


class Recording(pb_grpc.SceneServiceServicer):
    def __init__(self) -> None:
        self.seen: list[tuple[str, str | None]] = []

    def _token(self, method: str, context: grpc.ServicerContext) -> None:
        self.seen.append((method, dict(context.invocation_metadata()).get("authorization")))

    def GetScene(self, request: pb.SceneRef, context: grpc.ServicerContext) -> pb.SceneInfo:
        self._token("GetScene", context)
        if request.scene_id != 7:
            context.abort(grpc.StatusCode.NOT_FOUND, f"no scene {request.scene_id}")
        return pb.SceneInfo(scene_id=7, name="probe", state=pb.SCENE_STATE_PAUSED)

    def StreamEvents(self, request: pb.SceneRef, context: grpc.ServicerContext) -> Iterator[pb.SceneEvent]:
        self._token("StreamEvents", context)
        yield pb.SceneEvent(scene_id=request.scene_id, deleted=pb.Deleted())


@pytest.fixture
def fake() -> Iterator[tuple[str, Recording]]:
    service = Recording()
    server = grpc.server(futures.ThreadPoolExecutor(max_workers=2))
    pb_grpc.add_SceneServiceServicer_to_server(service, server)
    port = server.add_insecure_port("127.0.0.1:0")
    server.start()
    yield f"http://127.0.0.1:{port}", service
    server.stop(None)


def test_token_is_sent_with_calls_and_streams(fake: tuple[str, Recording]) -> None:
    address, service = fake
    with floe_client.connect(address, token="s3cret") as client:
        assert client.get(7).name == "probe"
        assert list(client.events(7)) == [floe_client.Deleted(7)]
        with pytest.raises(floe_client.NotFound, match="no scene 8"):
            client.get(8)
    with floe_client.connect(address) as anonymous:
        anonymous.get(7)
    assert service.seen == [
        ("GetScene", "Bearer s3cret"),
        ("StreamEvents", "Bearer s3cret"),
        ("GetScene", "Bearer s3cret"),
        ("GetScene", None),
    ]
