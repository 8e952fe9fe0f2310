"""The shipped gRPC stubs are what scripts/gen_stubs.py makes from proto/floe/v1/scenes.proto."""

from __future__ import annotations

import importlib.util
import pathlib

from conftest import ROOT

SCRIPT = ROOT / "client" / "python" / "scripts" / "gen_stubs.py"


def test_shipped_stubs_match_the_proto(tmp_path: pathlib.Path) -> None:
    spec = importlib.util.spec_from_file_location("gen_stubs", SCRIPT)
    assert spec and spec.loader
    gen = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(gen)
    written = gen.generate(tmp_path)
    assert [p.name for p in written] == list(gen.GENERATED)
    for path in written:
        shipped = gen.PACKAGE_DIR / path.name
        assert shipped.read_text() == path.read_text(), (
            f"{shipped} differs from what {SCRIPT.name} generates: run `python {SCRIPT.relative_to(ROOT)}`"
        )
