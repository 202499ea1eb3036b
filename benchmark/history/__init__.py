"""Nightly history: runs kept over time, compared with each other, and what changed.

* :mod:`benchmark.history.database`: the history database (SQLite or any
  SQLAlchemy URL) of runs, machines, commits and cell summaries.
* :mod:`benchmark.history.machine`: the machine, its load and the commit of a run.
* :mod:`benchmark.history.regressions`: changes of a run against earlier
  ones, and steps over the whole history.
* :mod:`benchmark.history.nightly`: a nightly run from start to site, speed
  changes repeated before they count.
"""
