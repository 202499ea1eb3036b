"""Closed-loop runs: a tracker's estimate steers a vehicle along a cable, and the scene renders what it sees next.

* :mod:`~benchmark.closedloop.route`: the cable's route in the seabed plane, and where a vehicle stands against it;
* :mod:`~benchmark.closedloop.vehicle`: the vehicle's state and the declared kinematic model a command moves it by;
* :mod:`~benchmark.closedloop.controller`: the cable-following PD law every tracker drives with.
"""
