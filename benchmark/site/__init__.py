"""The nightly site: static HTML pages of a history's latest run, readable from ``file://``.

* :mod:`benchmark.site.build`: :func:`build_site`, the pages and what each shows.
* :mod:`benchmark.site.figures`: trend plots and a cell's frames, drawn with matplotlib.
* :mod:`benchmark.site.tables`: tables that sort and filter in the browser (ITables, offline).
"""

from benchmark.site.build import build_site

__all__ = ["build_site"]
