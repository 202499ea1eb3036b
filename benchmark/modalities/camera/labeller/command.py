"""``trackbench label PATH``: label a camera sequence by hand in the browser."""

from __future__ import annotations

from pathlib import Path

import click


@click.command("label")
@click.argument("path", type=click.Path(path_type=Path))
@click.option(
    "--out",
    type=click.Path(dir_okay=False, path_type=Path),
    default=None,
    help="The image sequence file to save to (default: PATH itself; F.txt beside a folder F; V.txt beside V.avi).",
)
@click.option(
    "--port",
    type=click.IntRange(0, 65535),
    default=8765,
    show_default=True,
    help="Port on 127.0.0.1 (0: any free one; a fixed port keeps the page's unsaved drafts across restarts).",
)
@click.option("--no-browser", is_flag=True, help="Print the page's address without opening a browser.")
def label_command(path: Path, out: Path | None, port: int, no_browser: bool) -> None:
    """Label the cable in each frame of PATH, as the thesis' GroundTruthEditor does, on a page in the browser.

    PATH is an image sequence file, an image folder or a video (a video's
    frames are first written out as PNG images beside it).  Drag the ends
    of the two green borders onto the cable, or type d, alpha, w and beta;
    copy to the next frame, interpolate between key frames, mark frames
    without a cable, and save as an image sequence file (the previous one
    is kept as FILE.bak).  The page is served on 127.0.0.1 only, under a
    random token; Ctrl-C stops it.
    """
    import webbrowser

    import uvicorn

    from benchmark.modalities.camera.labeller.app import HOST, bind, create_app, new_token
    from benchmark.modalities.camera.labeller.document import open_document

    document = open_document(path, out)
    token = new_token()
    listening = bind(port)
    url = f"http://{HOST}:{listening.getsockname()[1]}/{token}/"
    click.echo(f"Labelling {len(document.images)} frames of {document.name}; saving to {document.output}", err=True)
    click.echo(url)
    if not no_browser:
        webbrowser.open(url)
    server = uvicorn.Server(uvicorn.Config(create_app(document, token), log_level="warning"))
    server.run(sockets=[listening])
