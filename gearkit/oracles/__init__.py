"""Independent oracles: the swept-tool cuts the tests and the bench hold the envelope kernel against.

One module per family (:mod:`~gearkit.oracles.involute`, :mod:`~gearkit.oracles.cycloid`,
:mod:`~gearkit.oracles.novikov`, :mod:`~gearkit.oracles.cam`). They share no code with the envelope
path: tool outlines and kinematics are written out again, and the cut is found by polygon booleans
or ray casts.
"""
