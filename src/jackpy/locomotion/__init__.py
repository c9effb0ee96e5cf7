"""Locomotion: terrain, jointed creatures walking, pronking and bouncing (Sims 1987).

Import-free on purpose: import the submodules you need (``jackpy.locomotion.terrain``, ...).
"""
