"""Reach that respects the workplace (issue 16): collision-aware reach verdicts
(:mod:`jackpy.planning.collision_reach`) and staged posture planning (:mod:`jackpy.planning.stages`).

Import-free: import the submodules you need.
"""
