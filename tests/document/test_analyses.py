"""The document's live strength analysis reads strength at the figure's posture."""

import numpy as np

from jackpy.analysis import Load, dof_strengths, joint_torques, utilisation
from jackpy.body.strength import strength_table
from jackpy.document import Document
from jackpy.document.session import default_scene


def test_live_strength_uses_the_posture_curves():
    """The live utilisation equals torque / strength-at-posture (the elbow's flexor curve), not the
    posture-blind peak table, and bending the elbow changes the elbow's strength it divides by."""
    env, base = default_scene()
    doc = Document(env)
    doc.scene_dir = base
    live = doc.analyses
    live.strength_live, live.load_kg = True, 6.0
    fig = doc.figure_of_interest()
    hand = "right_palm" if live.hand == "right" else "left_palm"
    elbow = f"{live.hand}_elbow"
    names = fig.dof_names()
    k = names.index(f"{elbow}[0]")
    seen = []
    for deg in (45.0, 100.0):
        fig.joint(elbow).displacement = np.radians(np.array([deg]))
        live.refresh(doc.env)
        assert live.strength is not None, live.strength_error
        tau = joint_torques(fig, [Load.held_mass(fig, hand, "grip", 6.0)])
        want = utilisation(fig, tau, dof_strengths(strength_table(fig, at_posture=True)))
        np.testing.assert_allclose(live.strength.utilisation, want, rtol=1e-9, atol=1e-12)
        seen.append(strength_table(fig, at_posture=True)[f"{elbow}[0]"])
    peak = strength_table(fig)[f"{elbow}[0]"]
    assert seen[0] != seen[1] and seen[0] != peak, (seen, peak)
    assert np.isfinite(live.strength.utilisation[k])
