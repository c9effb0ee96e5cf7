"""Segment centres of mass at de Leva's (1996) positions, measured by FK on generated figures."""

import numpy as np
import pytest

from jackpy.body.human import make_human
from jackpy.body.segment_inertia import DE_LEVA_STATURE, GROUPS, de_leva


def _com(fig, names):
    w = fig.world_transforms()
    m = np.array([fig.segment(n).mass for n in names])
    p = np.array([w[n][:3, :3] @ fig.segment(n).com + w[n][:3, 3] for n in names])
    return m @ p / m.sum()


@pytest.mark.parametrize("sex", ["male", "female"])
def test_de_leva_com_positions(sex):
    fig = make_human(sex, 50)
    fig.q = np.zeros(fig.ndof)  # zero pose: arms straight down
    table = de_leva(sex)
    elbow, wrist = (fig.site_world(*s)[:3, 3] for s in (("left_forearm", "base"), ("left_palm", "base")))
    fore = _com(fig, [m.format(side="left") for m in GROUPS["forearm"]])
    assert np.linalg.norm(fore - (elbow + (wrist - elbow) * table["forearm"]["com_pct"] / 100)) < 0.002
    ratio = fig.body_spec.stature / DE_LEVA_STATURE[sex]
    top = fig.site_world("head", "top")[1, 3]
    head = _com(fig, GROUPS["head"])
    want = top - table["head"]["com_pct"] / 100 * table["head"]["length_mm"] * 1e-3 * ratio
    assert head[1] == pytest.approx(want, abs=0.002)
    hip = fig.site_world("pelvis", "centre")[1, 3]
    trunk = _com(fig, GROUPS["upper_trunk"] + GROUPS["mid_trunk"] + GROUPS["lower_trunk"])
    length = table["trunk"]["length_mm"] * 1e-3 * ratio
    assert trunk[1] == pytest.approx(hip + length * (1 - table["trunk"]["com_pct"] / 100), abs=0.002)
    assert fig.total_mass == pytest.approx(fig.body_spec.mass, rel=1e-12)
