"""The revised NIOSH lifting equation (Waters et al. 1993; Applications Manual 1994)."""

import numpy as np
import pytest

from jackpy.ergonomics import ErgonomicsError, Lift, Task, assess, measure
from jackpy.ergonomics.niosh import am, cm, composite, coupling_type, dm, fm, hm, measured_origin, single_lift, vm


def test_standard_lifting_location_gives_23_kg():
    r = single_lift(Lift(load_kg=10.0, h=25, v=75, d=25, a=0, frequency=0.2, duration_h=1, coupling="good"), None)
    o = r["origin"]
    assert [o[k] for k in ("HM", "VM", "DM", "AM", "FM", "CM")] == [1.0] * 6
    assert r["RWL_kg"] == pytest.approx(23.0)
    assert r["LI"] == pytest.approx(10.0 / 23.0)


def test_multipliers_at_their_boundaries():
    assert (hm(20), hm(25), hm(50), hm(63), hm(63.1)) == (1.0, 1.0, 0.5, pytest.approx(25 / 63), 0.0)
    assert (vm(75), vm(0), vm(175), vm(175.1)) == (1.0, pytest.approx(0.775), pytest.approx(0.7), 0.0)
    assert (dm(10), dm(25), dm(175), dm(175.1)) == (1.0, pytest.approx(1.0), pytest.approx(0.82 + 4.5 / 175), 0.0)
    assert (am(0), am(90), am(135), am(135.1)) == (1.0, pytest.approx(0.712), pytest.approx(0.568), 0.0)
    assert cm("good", 30) == 1.0 and cm("fair", 74.9) == 0.95 and cm("fair", 75) == 1.0 and cm("poor", 80) == 0.9


@pytest.mark.parametrize("f,dur,v,expected", [
    (0.1, 1, 80, 1.00),    # below 0.2 lifts/min: 0.2
    (0.2, 1, 80, 1.00), (0.2, 1.01, 80, 0.95), (0.2, 2, 80, 0.95), (0.2, 2.01, 80, 0.85), (0.2, 8, 80, 0.85),
    (0.3, 1, 80, 0.97),    # between rows: the next higher frequency
    (1, 1, 80, 0.94), (4, 8, 80, 0.45), (9, 8, 74.9, 0.00), (9, 8, 75, 0.15),
    (12, 2, 70, 0.00), (12, 2, 75, 0.21), (15, 1, 74, 0.00), (15, 1, 75, 0.28),
])
def test_frequency_multiplier_table(f, dur, v, expected):
    assert fm(f, dur, v) == pytest.approx(expected)


@pytest.mark.parametrize("kw,match", [
    ({"frequency": 16.0}, "off the NIOSH frequency table"), ({"frequency": 0.0}, "frequency"),
    ({"frequency": -1.0}, "frequency"), ({"duration_h": 9.0}, "off the NIOSH frequency table"),
    ({"duration_h": 0.0}, "duration"), ({"load_kg": -2.0}, "load_kg"), ({"h": -1.0}, "h"),
    ({"coupling": "sticky"}, "coupling"), ({"d": None}, "vertical travel"),
])
def test_bad_lift_parameters_are_clear_errors(kw, match):
    lift = dict(load_kg=10.0, h=30, v=70, d=40, a=0)
    lift.update(kw)
    with pytest.raises(ErgonomicsError, match=match):
        single_lift(Lift(**lift), None)


def test_negative_task_load_is_refused():
    with pytest.raises(ErgonomicsError, match="load_kg"):
        Task(load_kg=-1.0)
    with pytest.raises(ErgonomicsError, match="unknown key"):
        Task.from_dict({"load": 3})


def test_coupling_decision_tree():
    assert coupling_type(Lift(container=True, optimal_object=True, optimal_handles=True), False) == "good"
    assert coupling_type(Lift(container=True, optimal_object=True, optimal_handles=False), True) == "fair"
    assert coupling_type(Lift(container=True, optimal_object=True, optimal_handles=False), False) == "poor"
    assert coupling_type(Lift(container=True, optimal_object=False), True) == "poor"
    assert coupling_type(Lift(container=False, optimal_object=False), True) == "poor"
    assert coupling_type(Lift(container=False, optimal_object=True, optimal_handles=True), False) == "good"


def test_composite_lifting_index_hand_computed():
    """Task A 10 kg at 1 lift/min, task B 15 kg at 2 lifts/min, both at the standard location for
    under an hour: STLI_B = 15 / (23 * 0.91) comes first; CLI = STLI_B + FILI_A (1/FM(3) - 1/FM(2))."""
    a = single_lift(Lift(load_kg=10, h=25, v=75, d=25, a=0, frequency=1, coupling="good"), None)
    b = single_lift(Lift(load_kg=15, h=25, v=75, d=25, a=0, frequency=2, coupling="good"), None)
    c = composite([a, b], 1.0)
    expected = 15 / (23 * 0.91) + (10 / 23) * (1 / 0.88 - 1 / 0.91)
    assert c["order"] == [1, 0]
    assert c["CLI"] == pytest.approx(expected)


def test_measured_from_the_posture_and_frame_independent(poser):
    for side in ("left", "right"):
        poser.arm(side, 60.0)
        poser.elbow(side, 60.0)
    p = measure(poser.f)
    grips = [poser.f.site_world(f"{s}_palm", "grip")[:3, 3] for s in ("left", "right")]
    ankles = [poser.f.world_transforms()[f"{s}_foot"][:3, 3] for s in ("left", "right")]
    mid, amid = np.mean(grips, axis=0), np.mean(ankles, axis=0)
    o = measured_origin(p)
    assert o["h"] == pytest.approx(100 * np.hypot(*(mid - amid)[[0, 2]]), abs=1e-6)
    assert o["v"] == pytest.approx(100 * mid[1], abs=1e-6)
    assert o["a"] == pytest.approx(0.0, abs=1e-6)
    # the same posture turned 70° about the vertical and moved: the same H, V, A
    c, s = np.cos(np.radians(70)), np.sin(np.radians(70))
    turn = np.array([[c, 0, s, 1.5], [0, 1, 0, 0], [-s, 0, c, -2.0], [0, 0, 0, 1]])
    poser.f.location = turn @ poser.f.location
    o2 = measured_origin(measure(poser.f))
    assert o2 == pytest.approx(o, abs=1e-6)


def test_twisted_trunk_gives_an_asymmetry_angle(poser):
    for side in ("left", "right"):
        poser.arm(side, 60.0)
    poser.spine(axial=40.0)
    r = assess(poser.f, ["niosh"], Task(lifts=[Lift(load_kg=8, d=40, coupling="good")]))["niosh"]
    o = r.worksheet["lifts"][0]["origin"]
    assert 10.0 < o["A_deg"] < 60.0
    assert o["AM"] == pytest.approx(1 - 0.0032 * o["A_deg"])
    assert r.score == pytest.approx(8 / r.worksheet["RWL_kg"])


def test_out_of_range_is_flagged_not_silently_scored(poser):
    r = assess(poser.f, ["niosh"], Task(lifts=[Lift(load_kg=5, h=70, v=80, d=30, a=0, coupling="good")]))["niosh"]
    assert r.worksheet["RWL_kg"] == 0.0
    assert any("beyond 63 cm" in f for f in r.flags)
    assert r.score == float("inf")


def test_destination_control_uses_the_lower_rwl():
    r = single_lift(Lift(load_kg=10, h=25, v=75, a=0, dest_v=150, dest_h=40, coupling="good"), None)
    assert r["origin"]["D_cm"] == pytest.approx(75)
    assert r["destination"]["HM"] == pytest.approx(25 / 40)
    assert r["RWL_kg"] == pytest.approx(r["destination"]["RWL_kg"])


def test_niosh_needs_a_lift(poser):
    with pytest.raises(ErgonomicsError, match="no lift"):
        assess(poser.f, ["niosh"], Task())
