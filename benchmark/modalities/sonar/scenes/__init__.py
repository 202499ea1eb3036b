"""Simulated multibeam sonar sequences.

**Sonar** (the ``sonar`` suite).  The multibeam echo-sounder data of Tena
Ruiz et al. (seeds/003, section 4): a vehicle runs along a pipe and its
sonar measures one swath of equiangular beams across the track per ping.
Each frame holds the swath (across-track positions and depths of the
returns, with range noise, spikes and missing beams) and the first pipe's
axis position, depth, burial and the beam spacing there.  The seabed has
slope, roughness correlated from ping to ping, ripples, sand waves whose
troughs a stiff pipe spans, trenches with spoil heaps and boulders; the
pipe may drift smoothly across the swath, and a second pipe may lie nearby.  Modules:

* :mod:`~benchmark.modalities.sonar.scenes.spec`: sequence definitions as data (the
  sonar, the vehicle, the seabed, the pipes);
* :mod:`~benchmark.modalities.sonar.scenes.seabed`: the seabed as a grid of depths
  over (ping, across-track position);
* :mod:`~benchmark.modalities.sonar.scenes.pipes`: where each pipe lies, how deep and
  how buried;
* :mod:`~benchmark.modalities.sonar.scenes.swath`: beams cast on seabed and pipes,
  and the sonar's errors;
* :mod:`~benchmark.modalities.sonar.scenes.scene`: :class:`SonarScene`.
"""
