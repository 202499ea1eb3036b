"""The nightly site: static HTML pages of a history's runs, readable from ``file://``.

* :mod:`benchmark.site.build`: :func:`build_site`, which pages a history has; drawing them in parallel and
  only where their inputs changed; the atomic switch to the new build.
* :mod:`benchmark.site.pages`: each kind of page and what it shows.
* :mod:`benchmark.site.compare`: any two runs side by side (the compare page and ``trackbench compare --html``).
* :mod:`benchmark.site.figures`: trends over the runs and a cell's frames, as interactive plotly figures.
* :mod:`benchmark.site.tables`: tables that sort and filter in the browser (ITables, offline).
"""

from benchmark.site.build import build_site

__all__ = ["build_site"]
