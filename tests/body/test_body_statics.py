"""Acceptance: static torques of a forward-reaching arm holding 5 kg against a hand calculation with
de Leva's (1996) masses and centre-of-mass positions; the shoulder twist zero is anatomical."""

import numpy as np
import pytest

from jackpy.analysis.statics import G, Load, joint_torques
from jackpy.body.human import make_human
from jackpy.body.segment_inertia import de_leva


def _pose(fig, tau_deg):
    fig.groups["left_shoulder_complex"].set_angles(fig, np.radians([90.0, 90.0, tau_deg]))


def _p(fig, seg, site):
    return fig.site_world(seg, site)[:3, 3]


@pytest.fixture(scope="module")
def male():
    return make_human("male", 50)


def test_forward_arm_thumb_up_at_zero_twist(male):
    _pose(male, 0.0)
    arm = _p(male, "left_palm", "base") - _p(male, "left_upper_arm", "base")
    assert arm[2] / np.linalg.norm(arm) > 0.99  # horizontal, forward
    thumb = _p(male, "left_thumb_3", "tip") - _p(male, "left_palm", "base")
    assert thumb[1] > 0.03  # thumb up
    axis = male.world_transforms()["left_forearm"][:3, :3] @ male.joint("left_elbow").dofs[0].axis
    assert abs(axis[0]) > 0.99  # the elbow flexes in the vertical plane: it carries the load
    g = male.groups["left_shoulder_complex"]
    assert g.lower[2] < -np.radians(60) and g.upper[2] > np.radians(60)  # well inside the twist range


@pytest.mark.parametrize("tau", [0.0, -45.0, 45.0])
def test_elbow_torque_matches_de_leva_hand_calculation(male, tau):
    _pose(male, tau)
    m = male.body_spec.mass
    table = de_leva("male")
    elbow, wrist = _p(male, "left_forearm", "base"), _p(male, "left_palm", "base")
    mcp3, grip = _p(male, "left_middle_1", "base"), _p(male, "left_palm", "grip")
    parts = [(m * table["forearm"]["mass_pct"] / 100, elbow + (wrist - elbow) * table["forearm"]["com_pct"] / 100),
             (m * table["hand"]["mass_pct"] / 100, wrist + (mcp3 - wrist) * table["hand"]["com_pct"] / 100),
             (5.0, grip)]
    moment = sum(np.cross(p - elbow, [0.0, -mass * G, 0.0]) for mass, p in parts)
    axis = male.world_transforms()["left_forearm"][:3, :3] @ male.joint("left_elbow").dofs[0].axis
    want = -axis @ moment
    load = Load.held_mass(male, "left_palm", "grip", 5.0)
    got = joint_torques(male, [load])[male.joint_dof_slice("left_elbow")][0]
    assert abs(want) > (18.0 if tau == 0 else 12.0)  # about 20 N m, times cos(twist) when twisted
    assert got == pytest.approx(want, rel=0.02)
