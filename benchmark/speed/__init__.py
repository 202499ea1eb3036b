"""``trackbench speed``: each tracker timed against the unavoidable work it does, as its plugin declares it.

:mod:`benchmark.speed.bounds` holds what plugins declare (bounds, goals,
the ``trackbench.speed`` entry-point group), :mod:`benchmark.speed.subjects`
makes a subject ready (frames in memory, model trained),
:mod:`benchmark.speed.measure` times it in alternating rounds and
:mod:`benchmark.speed.table` prints and writes the table.
"""
