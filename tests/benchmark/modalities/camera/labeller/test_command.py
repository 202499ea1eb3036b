"""``trackbench label``: a camera-modality command, serving on 127.0.0.1 under a token, opening the browser."""

from __future__ import annotations

import re
import socket
from pathlib import Path

import pytest
import uvicorn
from click.testing import CliRunner

from benchmark.cli import main


@pytest.fixture
def served(monkeypatch: pytest.MonkeyPatch) -> dict[str, object]:
    """Record what the command would serve and open, instead of serving and opening it."""
    seen: dict[str, object] = {}

    def run(server: uvicorn.Server, sockets: list[socket.socket]) -> None:
        (listening,) = sockets
        seen["address"] = listening.getsockname()
        listening.close()

    monkeypatch.setattr(uvicorn.Server, "run", run)
    monkeypatch.setattr("webbrowser.open", lambda url: seen.setdefault("opened", url))
    return seen


def test_label_is_a_command_of_the_camera_modality() -> None:
    result = CliRunner().invoke(main, ["--help"])
    assert result.exit_code == 0
    assert re.search(r"^\s+label\s", result.output, re.MULTILINE)


@pytest.mark.parametrize(("flags", "opens"), [((), True), (("--no-browser",), False)])
def test_label_serves_on_localhost_under_a_token_and_opens_the_page(
    served: dict[str, object], image_folder: Path, flags: tuple[str, ...], opens: bool
) -> None:
    result = CliRunner().invoke(main, ["label", str(image_folder), "--port", "0", *flags])
    assert result.exit_code == 0, result.output
    url = result.stdout.strip()
    host, port = served["address"]
    assert host == "127.0.0.1"
    assert re.fullmatch(rf"http://127\.0\.0\.1:{port}/[A-Za-z0-9_-]{{32}}/", url)
    assert served.get("opened") == (url if opens else None)


def test_label_of_a_missing_path_is_an_error_naming_it(tmp_path: Path) -> None:
    result = CliRunner().invoke(main, ["label", str(tmp_path / "missing"), "--no-browser"])
    assert result.exit_code == 2
    assert "missing: no such dataset" in result.output
