"""Seated support: a figure sitting on a seat keeps its ischia on it and its feet on the floor or a
footrest while the user drags its hands, head or torso (issue 19 item 1; ``jackpy.body.seated``).

:func:`jackpy.behaviors.manipulation.sit` puts the figure on the seat (``jackpy.body.seated.sit``:
thighs horizontal, ischial tuberosities on the seat, soles flat on the footrest where the shanks
reach) and sets ``state.seat``. Then, every frame, this behavior:

- claims the root and roots the figure through the pelvis (the automatic root leaves it alone, the
  stepping and standing balance are off: the balance behavior sets no COM goal for a pelvis root);
  the IK cannot move the root, so the pelvis, and with it the two seat contacts, stay put;
- checks the seat contacts (``pelvis.left_ischium``/``right_ischium``) against the seat: if they
  are off it (the figure was moved, the seat was raised) the figure is moved back, at most
  ``anchor_rate`` per frame, so the contacts end on the seat plane where they were put down;
- leaves the feet to the feet behavior: each rests where ``sit`` put it (ball position, sole flat,
  heel on the footrest plane); a foot the shank cannot bring down to the footrest hangs, held where
  it is (``hold``, heel free).

[decision] The pelvis does not tilt on the ischia: a seated reach leans by the spine (the hands
behavior's lean), as in the seated posture of ANSUR II. :func:`~jackpy.behaviors.manipulation.stand_up`
clears the seat; the automatic root then chooses the root again.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from jackpy.behaviors.base import BehaviorBase, param

if TYPE_CHECKING:
    from jackpy.behaviors.loop import Frame

#: the seat contact sites on the pelvis (the standard human's ischial tuberosities)
CONTACT_SITES = ("left_ischium", "right_ischium")


@dataclass
class SeatParams:
    anchor_rate: float = param(0.003, "largest correction per frame of seat contacts off the seat", "mm",
                               (0.0, 0.1))


def contact_points(frame: "Frame") -> np.ndarray:
    """World points (2, 3) of the seat contact sites at the frame start."""
    pelvis = frame.anatomy.pelvis
    return np.array([frame.site(pelvis, s)[:3, 3] for s in CONTACT_SITES])


class Seat(BehaviorBase):
    """Holds a seated figure on its seat contacts (pelvis root) while ``state.seat`` is set."""

    name = "seat"
    order = 12

    def __init__(self, params: SeatParams | None = None, enabled: bool = True) -> None:
        super().__init__(params or SeatParams(), enabled)

    def update(self, frame: "Frame") -> None:
        st = frame.state
        if st.seat is None:
            return
        if st.root != "pelvis":
            frame.set_root("pelvis")
            frame.note("root -> pelvis (seated)")
        st.root_claimed = True
        err = (st.seat.contacts - contact_points(frame)).mean(axis=0)
        n = float(np.linalg.norm(err))
        if n < 1e-7:
            return
        loc = frame.figure.location.copy()
        loc[:3, 3] += err * min(1.0, self.params.anchor_rate / n)
        frame.figure.location = loc
        frame._refresh()
