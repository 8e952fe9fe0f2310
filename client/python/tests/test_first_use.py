"""What a new user meets first: a missing optional dependency or a server binary that is not
where the call says is named, with what to do, instead of a bare import or OS error."""

from __future__ import annotations

import sys

import pytest

import floe_client.local
from floe_client import export


def test_to_dataframe_without_pandas_names_the_extra(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "pandas", None)  # import pandas now fails
    with pytest.raises(ModuleNotFoundError, match=r"floe-client\[pandas\]"):
        export.to_dataframe(None)  # type: ignore[arg-type]


def test_a_server_binary_that_is_not_there_is_named(tmp_path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)  # outside the repository, as a notebook often is
    with pytest.raises(FileNotFoundError, match=r"no floe binary at 'target/release/floe'.*cargo build"):
        floe_client.local.Server("target/release/floe")
    monkeypatch.setenv("PATH", str(tmp_path))
    with pytest.raises(FileNotFoundError, match=r"no 'floe' on PATH"):
        floe_client.local.Server()
