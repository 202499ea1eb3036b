"""The labeller's web app: the page, the frames by index, conversions between states and borders, saving.

Every URL starts with a random token (``/TOKEN/...``); any other request is
refused with 403, and one addressed to a host name other than ``127.0.0.1``
or ``localhost`` with 400, so that another page of the browser, or another
user of the machine, cannot read the frames or overwrite the labels.  Frames are served
by their index only, and the page's files by a fixed list of names: no URL
names a path on disk.  The server is meant for ``127.0.0.1`` only
(:func:`bind`).

The page holds the labels being edited; it asks the app to convert a cable
state ``(d, alpha, w, beta)`` into its two border segments and two dragged
border lines back into a state, with :func:`~benchmark.modalities.camera.geometry.cable_borders`
and :func:`~benchmark.modalities.camera.geometry.cable_from_borders`
(``conventions.md`` section 1), so that the cable geometry lives in one
place.  All coordinates on the page are pixel coordinates ``(u, v)``.
"""

from __future__ import annotations

import math
import secrets
import socket
from importlib import resources
from typing import Annotated, Any

from pydantic import BaseModel, ConfigDict, Field, ValidationError
from starlette.applications import Starlette
from starlette.concurrency import run_in_threadpool
from starlette.middleware.trustedhost import TrustedHostMiddleware
from starlette.requests import Request
from starlette.responses import JSONResponse, PlainTextResponse, Response
from starlette.routing import Mount, Route
from starlette.types import ASGIApp, Receive, Scope, Send

from benchmark.errors import DataError
from benchmark.modalities.camera.draw import chord_ends
from benchmark.modalities.camera.geometry import ImageSize, Line, cable_borders, cable_from_borders, model_to_pixel
from benchmark.modalities.camera.labeller.document import LabelDocument
from benchmark.modalities.camera.model import UNKNOWN_CABLE, CableState

HOST = "127.0.0.1"
"""The only address the labeller listens on."""

STATIC_FILES = {"labeller.js": "text/javascript", "labeller.css": "text/css"}
"""The page's files beside ``index.html``, and their media types: the only files served."""

Finite = Annotated[float, Field(allow_inf_nan=False)]
Point = tuple[Finite, Finite]
Segment = tuple[Point, Point]
StateValues = tuple[Finite, Finite, Finite, Finite]


class _Body(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


class StateBody(_Body):
    """A cable state ``[d, alpha, w, beta]`` (px, rad, px, rad)."""

    state: StateValues


class BordersBody(_Body):
    """Two border lines, each through two pixel points ``[[u, v], [u, v]]``."""

    left: Segment
    right: Segment


class SaveBody(_Body):
    """One state per frame; null for a frame without a cable (unlabelled or no cable visible)."""

    states: list[StateValues | None]


def new_token() -> str:
    """A random URL token (:func:`secrets.token_urlsafe`)."""
    return secrets.token_urlsafe(24)


def bind(port: int) -> socket.socket:
    """A listening socket on :data:`HOST` and ``port`` (0: any free port).

    Raises
    ------
    DataError
        If the port cannot be had (in use, not allowed), naming it.
    """
    try:
        return socket.create_server((HOST, port))
    except OSError as exc:
        raise DataError(f"port {port} on {HOST}: cannot listen: {exc.strerror or exc}") from None


def border_segment(line: Line, size: ImageSize) -> list[list[float]]:
    """Two pixel points of a border, top one first: the ends of its chord through the image.

    A border that misses the image, or only grazes a corner (a chord
    shorter than a pixel, whose ends could not be dragged apart), gets the
    points half an image diagonal either side of its point nearest the
    image centre.
    """
    ends = chord_ends(line, size)
    if ends is None or math.dist(*ends) < 1.0:
        x0, y0 = line.nearest_point_to_origin()
        reach = math.hypot(*size) / 2.0
        ends = (x0 - reach * line.dx, y0 - reach * line.dy), (x0 + reach * line.dx, y0 + reach * line.dy)
    pixels = sorted((model_to_pixel(x, y, size)[::-1] for x, y in ends))
    return [[u, v] for v, u in pixels]


def drawing(state: CableState, size: ImageSize) -> dict[str, Any]:
    """What the page draws for a state: the state and its left and right border segments in pixels."""
    left, right = cable_borders(state)
    return {
        "state": list(state.as_array()),
        "left": border_segment(left, size),
        "right": border_segment(right, size),
    }


def state_of_borders(body: BordersBody, size: ImageSize) -> CableState:
    """The cable state whose borders pass through the two given pixel segments (:func:`cable_from_borders`)."""
    left, right = (Line.from_pixels(p, q, size) for p, q in (body.left, body.right))
    return cable_from_borders(left, right)


def _page_file(name: str) -> str:
    return resources.files(__package__).joinpath("static", name).read_text(encoding="utf-8")


def _bad_request(exc: Exception) -> JSONResponse:
    return JSONResponse({"error": str(exc)}, status_code=422)


class TokenGate:
    """ASGI middleware that refuses (403) every request whose path does not start with ``/TOKEN``."""

    def __init__(self, app: ASGIApp, token: str) -> None:
        self.app = app
        self.token = token

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] == "http":
            first = scope["path"].lstrip("/").partition("/")[0]
            if not secrets.compare_digest(first.encode(), self.token.encode()):
                await PlainTextResponse("Forbidden", status_code=403)(scope, receive, send)
                return
        await self.app(scope, receive, send)


def create_app(document: LabelDocument, token: str) -> Starlette:
    """The labeller's app for ``document``, reachable under ``/TOKEN/`` only.

    Routes (below ``/TOKEN``): ``/`` the page; ``/static/NAME`` its files
    (:data:`STATIC_FILES`); ``GET /api/sequence`` the frames' names, size
    and saved states; ``GET /frames/INDEX`` a frame as PNG;
    ``POST /api/borders-of`` a state's border segments; ``POST
    /api/state-of`` the state of two border segments; ``POST /api/save``
    write the states.  A malformed body is answered with 422 and a message.

    References
    ----------
    seeds/000, appendix B; ``conventions.md`` sections 1 and 2.
    """
    size = document.size
    page = _page_file("index.html")

    async def index(request: Request) -> Response:
        return Response(page, media_type="text/html", headers={"Cache-Control": "no-store"})

    async def static(request: Request) -> Response:
        name = request.path_params["name"]
        if name not in STATIC_FILES:
            return PlainTextResponse("Not Found", status_code=404)
        return Response(_page_file(name), media_type=STATIC_FILES[name], headers={"Cache-Control": "no-store"})

    async def sequence(request: Request) -> Response:
        revision = await run_in_threadpool(lambda: document.revision)
        return JSONResponse(
            {
                "name": document.name,
                "output": str(document.output),
                "width": size[0],
                "height": size[1],
                "images": [image.name for image in document.images],
                "states": [list(state.as_array()) if state.is_known else None for state in document.states],
                "revision": revision,
            }
        )

    async def frame(request: Request) -> Response:
        index = request.path_params["index"]
        if not 0 <= index < len(document.images):
            return PlainTextResponse("Not Found", status_code=404)
        try:
            data = await run_in_threadpool(document.frame_png, index)
        except DataError as exc:
            return PlainTextResponse(str(exc), status_code=500)
        return Response(data, media_type="image/png", headers={"Cache-Control": "private, max-age=3600"})

    async def borders_of(request: Request) -> Response:
        try:
            body = StateBody.model_validate_json(await request.body())
            return JSONResponse(drawing(CableState(*body.state), size))
        except (ValidationError, ValueError) as exc:
            return _bad_request(exc)

    async def state_of(request: Request) -> Response:
        try:
            body = BordersBody.model_validate_json(await request.body())
            return JSONResponse(drawing(state_of_borders(body, size), size))
        except (ValidationError, ValueError) as exc:
            return _bad_request(exc)

    async def save(request: Request) -> Response:
        try:
            body = SaveBody.model_validate_json(await request.body())
        except ValidationError as exc:
            return _bad_request(exc)
        states = [CableState(*values) if values is not None else UNKNOWN_CABLE for values in body.states]
        try:
            revision = await run_in_threadpool(document.save, states)
        except DataError as exc:
            return JSONResponse({"error": str(exc)}, status_code=409)
        return JSONResponse({"output": str(document.output), "revision": revision})

    routes = [
        Route("/", index),
        Route("/static/{name}", static),
        Route("/api/sequence", sequence),
        Route("/frames/{index:int}", frame),
        Route("/api/borders-of", borders_of, methods=["POST"]),
        Route("/api/state-of", state_of, methods=["POST"]),
        Route("/api/save", save, methods=["POST"]),
    ]
    app = Starlette(routes=[Mount(f"/{token}", routes=routes)])
    app.add_middleware(TokenGate, token=token)
    # A page of another site that points a name of its own at 127.0.0.1 (DNS rebinding) sends that name.
    app.add_middleware(TrustedHostMiddleware, allowed_hosts=[HOST, "localhost"])
    return app
