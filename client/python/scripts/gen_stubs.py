"""Regenerates the gRPC stubs shipped in floe_client/_proto from proto/floe/v1/scenes.proto.

Run after any change to the .proto (with the test extras installed, which pin grpcio-tools):

    python client/python/scripts/gen_stubs.py

``--out DIR`` writes them elsewhere (the test that checks the shipped stubs match the
.proto regenerates into a temporary directory and compares).
"""

from __future__ import annotations

import argparse
import pathlib
import sys
import tempfile

HERE = pathlib.Path(__file__).resolve().parent
PROTO_ROOT = HERE.parents[2] / "proto"
PROTO = "floe/v1/scenes.proto"
PACKAGE_DIR = HERE.parent / "python" / "floe_client" / "_proto"
# protoc names the messages module after the .proto's path; the stubs live in one flat
# package, so the service module imports it relatively.
ABSOLUTE_IMPORT = "from floe.v1 import scenes_pb2 as"
RELATIVE_IMPORT = "from . import scenes_pb2 as"
GENERATED = ("scenes_pb2.py", "scenes_pb2.pyi", "scenes_pb2_grpc.py")


def generate(out: pathlib.Path) -> list[pathlib.Path]:
    """Writes the generated modules into ``out`` and returns their paths."""
    from grpc_tools import protoc  # the test extra; not needed at run time

    with tempfile.TemporaryDirectory() as tmp:
        args = [
            "grpc_tools.protoc",
            f"-I{PROTO_ROOT}",
            f"--python_out={tmp}",
            f"--pyi_out={tmp}",
            f"--grpc_python_out={tmp}",
            str(PROTO_ROOT / PROTO),
        ]
        if protoc.main(args) != 0:
            raise RuntimeError(f"protoc failed on {PROTO_ROOT / PROTO}")
        out.mkdir(parents=True, exist_ok=True)
        written = []
        for name in GENERATED:
            text = (pathlib.Path(tmp) / "floe" / "v1" / name).read_text()
            if name.endswith("_grpc.py"):
                if ABSOLUTE_IMPORT not in text:
                    raise RuntimeError(f"{name}: no '{ABSOLUTE_IMPORT}' line to make relative")
                text = text.replace(ABSOLUTE_IMPORT, RELATIVE_IMPORT)
            (out / name).write_text(text)
            written.append(out / name)
        return written


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=pathlib.Path, default=PACKAGE_DIR, help="output directory")
    args = parser.parse_args()
    for path in generate(args.out):
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
