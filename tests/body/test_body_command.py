"""``jackpy human`` and rescaling in place."""

import numpy as np
import pytest

from jackpy.body.human import SUPPORT_SITES, attach_groups, make_human, rescale_in_place
from jackpy.cli import main


def test_human_command_writes_fig_and_glb(tmp_path, capsys):
    out = tmp_path / "f5.fig"
    assert main(["human", "--sex", "female", "--percentile", "5", "-o", str(out)]) == 0
    assert (tmp_path / "f5_psurf" / "head.pss").exists()
    from jackpy.peabody.reader import load

    fig = load(out).figures["female_p5"]
    attach_groups(fig)
    ref = make_human("female", 5)
    assert np.allclose(fig.q, ref.q, atol=1e-9)
    assert fig.site_world("head", "top")[1, 3] == pytest.approx(ref.body_spec.stature, abs=1e-6)
    assert fig.total_mass == pytest.approx(ref.total_mass, rel=1e-9)
    assert main(["human", "--sex", "male", "--set", "stature=180cm", "--set", "hand.length=p95",
                 "-o", str(tmp_path / "m.glb")]) == 0
    assert (tmp_path / "m.glb").stat().st_size > 10_000


@pytest.mark.parametrize("argv,message", [
    (["--percentile", "0"], "percentile"), (["--population", "nasa"], "unknown population"),
    (["--set", "tail.length=3"], "no dimension"), (["--set", "stature=tall"], "bad value"),
    (["--set", "mass=70cm"], "measured in"),
])
def test_human_command_user_errors(tmp_path, capsys, argv, message):
    assert main(["human", "--sex", "male", *argv, "-o", str(tmp_path / "x.fig")]) != 0
    err = capsys.readouterr().err
    assert message in err and "Traceback" not in err and len(err.strip().splitlines()) == 1


def test_rescale_in_place_keeps_posture_and_floor():
    fig = make_human("female", 50)
    fig.groups["spine"].set_angles(fig, np.radians([20.0, 0.0, 5.0]))
    fig.joint("left_knee").displacement = np.radians([30.0])
    q = fig.q
    spine = fig.groups["spine"].angles.copy()
    x, z = fig.location[0, 3], fig.location[2, 3]
    floor = min(fig.site_world(*s)[1, 3] for s in SUPPORT_SITES)
    rescale_in_place(fig, "male", 95)
    assert np.allclose(fig.q, q)
    assert np.allclose(fig.groups["spine"].angles, spine)
    assert (fig.location[0, 3], fig.location[2, 3]) == (x, z)
    assert min(fig.site_world(*s)[1, 3] for s in SUPPORT_SITES) == pytest.approx(floor)
    assert fig.body_spec.sex == "male" and fig.total_mass == pytest.approx(fig.body_spec.mass)
    ref = make_human("male", 95)
    assert fig.site_location("left_thigh", "knee") == pytest.approx(ref.site_location("left_thigh", "knee"))
