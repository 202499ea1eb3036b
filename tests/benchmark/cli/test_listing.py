"""``trackbench list`` and ``--help`` import no heavy dependency: plugins load those when a tracker runs.

Timed nowhere (a loaded machine would make that flaky): the test asks a
fresh process which modules listing loaded.
"""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

HEAVY = ("numba", "sklearn", "scipy", "pandas", "matplotlib", "rosbags", "uvicorn", "starlette", "sqlalchemy")
"""What only building, fitting or running a tracker, or a command's own work, may import."""

LOADED = """
import json, sys

from benchmark.cli import main

try:
    main(sys.argv[1:], prog_name="trackbench")
except SystemExit as exc:
    code = exc.code
print(json.dumps({"exit": code, "modules": sorted({name.partition(".")[0] for name in sys.modules})}))
"""


@pytest.mark.parametrize("arguments", [["list"], ["--help"]])
def test_listing_imports_none_of_the_heavy_dependencies(arguments: list[str]) -> None:
    ran = subprocess.run([sys.executable, "-c", LOADED, *arguments], capture_output=True, text=True, check=False)
    assert ran.returncode == 0, ran.stderr
    report = json.loads(ran.stdout.splitlines()[-1])
    assert report["exit"] == 0, ran.stderr
    assert sorted(set(HEAVY) & set(report["modules"])) == []
    if arguments == ["list"]:  # every first-party tracker was listed, so every plugin was imported
        assert {"trackbench_condensation", "trackbench_texture", "trackbench_sonar"} <= set(report["modules"])
        assert "texture-paper" in ran.stdout and "sonar_pf" in ran.stdout

