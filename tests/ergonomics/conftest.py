"""Posing the standard human by the angles the methods measure (degrees), for the ergonomics tests.

Every helper sets joint displacements or group angles only; the tests then *measure* the posture,
so a wrong measurement or a wrong pose fails them."""

from __future__ import annotations

import numpy as np
import pytest

from jackpy.body import make_human, set_neutral_posture
from jackpy.body.human import place_on_floor
from jackpy.peabody.model import Figure


class Poser:
    """Sets the posture of one standard human, starting from neutral standing."""

    def __init__(self, figure: Figure) -> None:
        self.f = figure
        self.home = figure.location.copy()

    def neutral(self) -> Figure:
        self.f.location = self.home.copy()
        set_neutral_posture(self.f)
        return self.f

    def arm(self, side: str, elevation: float, plane: float = 90.0, twist: float = 0.0) -> None:
        """Shoulder complex: total elevation, plane (90 = forward, 0 = sideways), degrees."""
        self.f.groups[f"{side}_shoulder_complex"].set_angles(self.f, np.radians([elevation, plane, twist]))

    def joint(self, name: str, *deg: float) -> None:
        self.f.joint(name).displacement = np.radians(np.array(deg, dtype=float))

    def elbow(self, side: str, deg: float) -> None:
        self.joint(f"{side}_elbow", deg)

    def wrist(self, side: str, flexion: float = 0.0, deviation: float = 0.0) -> None:
        self.joint(f"{side}_wrist", deviation, flexion)

    def neck(self, flexion: float = 0.0, side_bend: float = 0.0, twist: float = 0.0) -> None:
        self.joint("atlanto_occipital", twist, side_bend, flexion)

    def spine(self, flexion: float = 0.0, lateral: float = 0.0, axial: float = 0.0) -> None:
        self.f.groups["spine"].set_angles(self.f, np.radians([flexion, lateral, axial]))

    def hinge(self, deg: float) -> None:
        """Bend forward at the hips by ``deg`` with straight legs: the pelvis pitches forward about the
        hip centres, the hips flex by the same angle so the thighs stay vertical."""
        c, s = np.cos(np.radians(deg)), np.sin(np.radians(deg))
        rot = np.eye(4)
        rot[1:3, 1:3] = [[c, -s], [s, c]]
        self.f.location = self.home @ rot
        for side in ("left", "right"):
            d = self.f.joint(f"{side}_hip").displacement
            d[2] = np.radians(deg)
            self.f.joint(f"{side}_hip").displacement = d
        place_on_floor(self.f)

    def knees(self, deg: float) -> None:
        for side in ("left", "right"):
            self.joint(f"{side}_knee", deg)
        place_on_floor(self.f)

    def lift_foot(self, side: str) -> None:
        """Raise one foot about 10 cm by bending its hip 45° and knee 90° (the other stays down)."""
        self.joint(f"{side}_hip", 0.0, 0.0, 45.0)
        self.joint(f"{side}_knee", 90.0)
        place_on_floor(self.f)


@pytest.fixture(scope="session")
def human() -> Figure:
    return make_human("male", 50)


@pytest.fixture
def poser(human: Figure) -> Poser:
    p = Poser(human)
    p.neutral()
    yield p
    p.neutral()

