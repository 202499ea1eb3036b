"""``python -m benchmark.cli``: the ``trackbench`` command line."""

from benchmark.cli import main

main(prog_name="trackbench")
