"""The labeller's HTTP app through starlette's test client: the token, no paths from URLs, conversions, saving."""

from __future__ import annotations

import math
from pathlib import Path

import cv2
import numpy as np
import pytest
from hypothesis import given
from starlette.testclient import TestClient

from benchmark.modalities.camera.geometry import Line, cable_borders, pixel_to_model
from benchmark.modalities.camera.io.sequence_file import read_sequence_file
from benchmark.modalities.camera.labeller.app import BordersBody, create_app, drawing, state_of_borders
from benchmark.modalities.camera.labeller.document import LabelDocument, open_document
from benchmark.modalities.camera.model import CableState
from benchmark.modalities.camera.strategies import cable_states

from .conftest import N_FRAMES, SIZE

TOKEN = "secret-token"


@pytest.fixture
def document(image_folder: Path) -> LabelDocument:
    return open_document(image_folder)


@pytest.fixture
def client(document: LabelDocument) -> TestClient:
    return TestClient(create_app(document, TOKEN), base_url="http://127.0.0.1")


def distance(line: Line, pixel: tuple[float, float]) -> float:
    """Distance in px of a pixel point from a line in model coordinates."""
    x, y = pixel_to_model(*pixel, SIZE)
    return abs((x - line.x0) * line.dy - (y - line.y0) * line.dx)


@pytest.mark.parametrize("path", ["/", "/api/sequence", "/frames/0", "/wrong-token/frames/0", f"/{TOKEN}x/frames/0"])
def test_a_request_without_the_token_is_forbidden(client: TestClient, path: str) -> None:
    assert client.get(path).status_code == 403


def test_a_request_for_another_host_name_is_refused(client: TestClient) -> None:
    assert client.get(f"/{TOKEN}/api/sequence", headers={"Host": "attacker.example"}).status_code == 400
    assert client.get(f"/{TOKEN}/api/sequence", headers={"Host": "localhost:8765"}).status_code == 200


def test_a_save_without_the_token_is_forbidden_and_writes_nothing(client: TestClient, document: LabelDocument) -> None:
    assert client.post("/api/save", json={"states": [None] * N_FRAMES}).status_code == 403
    assert not document.output.exists()


@pytest.mark.parametrize(
    "path",
    [
        "frames/..%2F..%2Fframes.txt",
        "frames/%2Fetc%2Fpasswd",
        "frames/frame0.png",
        f"frames/{N_FRAMES}",
        "frames/-1",
        "static/..%2Fapp.py",
        "static/%2E%2E%2Fdocument.py",
        "static/index.html",
        "static/app.py",
    ],
)
def test_no_url_names_a_file(client: TestClient, path: str) -> None:
    assert client.get(f"/{TOKEN}/{path}").status_code == 404


def test_the_page_and_its_files_are_served(client: TestClient) -> None:
    page = client.get(f"/{TOKEN}/")
    assert page.status_code == 200 and 'src="static/labeller.js"' in page.text
    assert client.get(f"/{TOKEN}/static/labeller.js").headers["content-type"].startswith("text/javascript")


def test_frames_are_served_by_index_as_png(client: TestClient, image_folder: Path) -> None:
    response = client.get(f"/{TOKEN}/frames/3")
    assert response.headers["content-type"] == "image/png"
    decoded = cv2.imdecode(np.frombuffer(response.content, np.uint8), cv2.IMREAD_UNCHANGED)
    np.testing.assert_array_equal(decoded, cv2.imread(str(image_folder / "frame3.png"), cv2.IMREAD_GRAYSCALE))


def test_the_sequence_lists_frames_size_and_states(client: TestClient, document: LabelDocument) -> None:
    data = client.get(f"/{TOKEN}/api/sequence").json()
    assert (data["width"], data["height"]) == SIZE
    assert data["images"] == [f"frame{i}.png" for i in range(N_FRAMES)]
    assert data["states"] == [None] * N_FRAMES
    assert data["output"] == str(document.output)


def test_a_states_borders_are_its_geometry_chords(client: TestClient) -> None:
    state = CableState(3.0, 0.2, 14.0, 0.05)
    data = client.post(f"/{TOKEN}/api/borders-of", json={"state": list(state.as_array())}).json()
    for line, segment in zip(cable_borders(state), (data["left"], data["right"]), strict=True):
        (u0, v0), (u1, v1) = segment
        assert v0 <= v1 and math.hypot(u1 - u0, v1 - v0) > 40
        assert max(distance(line, (u0, v0)), distance(line, (u1, v1))) < 1e-9
        assert {v0, v1} == {0.0, SIZE[1] - 1.0}


def test_dragged_borders_become_a_state_whose_borders_pass_through_them(client: TestClient) -> None:
    left, right = [[20.0, 0.0], [24.0, 47.0]], [[40.0, 0.0], [37.0, 47.0]]
    data = client.post(f"/{TOKEN}/api/state-of", json={"left": left, "right": right}).json()
    lines = cable_borders(CableState(*data["state"]))
    for line, segment in zip(lines, (left, right), strict=True):
        assert max(distance(line, tuple(point)) for point in segment) < 1e-9
    assert data["left"][0] == pytest.approx(left[0]) and data["right"][1] == pytest.approx(right[1])


@pytest.mark.parametrize(
    ("route", "body"),
    [
        ("borders-of", {"state": [0, 0, 10]}),
        ("borders-of", {"state": [0, "nan", 10, 0]}),
        ("borders-of", {"state": [0, 0, 1e308, 0], "extra": 1}),
        ("state-of", {"left": [[1, 1], [1, 1]], "right": [[5, 0], [5, 9]]}),
        ("state-of", {"left": [[1, 1]], "right": [[5, 0], [5, 9]]}),
        ("save", {"states": [[0, 0, 10, "inf"]] * N_FRAMES}),
        ("save", {"states": "none"}),
    ],
)
def test_a_malformed_body_is_refused_with_a_message(client: TestClient, route: str, body: object) -> None:
    response = client.post(f"/{TOKEN}/api/{route}", json=body)
    assert response.status_code == 422
    assert response.json()["error"]


def test_save_writes_the_sequence_file_and_a_backup(client: TestClient, document: LabelDocument) -> None:
    states = [[float(i), 0.01 * i, 12.0, 0.0] if i != 2 else None for i in range(N_FRAMES)]
    first = client.post(f"/{TOKEN}/api/save", json={"states": states}).json()
    rows = read_sequence_file(document.output)
    assert [row.cable.as_array().tolist() if row.cable.is_known else None for row in rows] == states
    assert first["revision"] == client.get(f"/{TOKEN}/api/sequence").json()["revision"]
    before = document.output.read_bytes()
    second = client.post(f"/{TOKEN}/api/save", json={"states": [None] * N_FRAMES}).json()
    assert document.backup.read_bytes() == before
    assert second["revision"] != first["revision"]
    assert client.get(f"/{TOKEN}/api/sequence").json()["states"] == [None] * N_FRAMES


def test_a_save_with_the_wrong_number_of_frames_is_refused(client: TestClient, document: LabelDocument) -> None:
    response = client.post(f"/{TOKEN}/api/save", json={"states": [None]})
    assert response.status_code == 409 and "1 states for 6 frames" in response.json()["error"]
    assert not document.output.exists()


@given(cable_states(*SIZE))
def test_a_states_drawn_borders_give_back_a_state_with_the_same_borders(state: CableState) -> None:
    drawn = drawing(state, SIZE)
    back = state_of_borders(BordersBody(left=drawn["left"], right=drawn["right"]), SIZE)
    for line, segment in zip(cable_borders(back), (drawn["left"], drawn["right"]), strict=True):
        assert max(distance(line, tuple(point)) for point in segment) < 1e-6
    assert math.dist(*drawn["left"]) >= 1.0 and math.dist(*drawn["right"]) >= 1.0
