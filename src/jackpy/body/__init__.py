"""The standard human figure: structure, anthropometric scaling (SASS), mass, strength and surfaces.

Public entry points: :func:`make_human`, :func:`rescale_in_place`, :func:`body_spec`,
:func:`load_population`; strength in :mod:`jackpy.body.strength`. See docs/body.md.
"""

from jackpy.body.anthropometry import (
           AnthropometryError,
           available_populations,
           load_population,
)
from jackpy.body.human import (
           body_spec,
           make_human,
           rescale_in_place,
           set_neutral_posture,
)
from jackpy.body.sass import (
           BodySpec,
           ScalingError,
           set_dimension,
           set_mass,
           set_stature,
           spec_for,
)

__all__ = ["AnthropometryError", "BodySpec", "ScalingError", "available_populations", "body_spec",
           "load_population", "make_human", "rescale_in_place", "set_dimension", "set_mass",
           "set_neutral_posture", "set_stature", "spec_for"]
