"""URDF and MJCF export: both load in their ecosystems' parsers (mujoco, yourdfpy) and put every site
where jackpy's forward kinematics does, at random postures, to 1e-9 m."""

from __future__ import annotations

import io
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from jackpy.body import make_human
from jackpy.cli import main
from jackpy.motion import robot_export as rx
from jackpy.peabody.model import Dof, Figure, Joint, Segment

mujoco = pytest.importorskip("mujoco")
yourdfpy = pytest.importorskip("yourdfpy")

TOL = 1e-9


def _slider() -> Figure:
    """A small figure with translation DOFs, a 3-DOF joint and an off-axis site (rooted mid-chain)."""
    f = Figure("slider")
    for name in ("a", "b", "c"):
        s = f.add_segment(Segment(name, mass=1.0, com=np.array([0.0, 0.1, 0.0]),
                                  inertia=np.diag([0.01, 0.02, 0.03])))
        s.add_site("base")
        tip = np.eye(4)
        tip[:3, 3] = (0.1, 0.3, -0.05)
        tip[:3, :3] = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
        s.add_site("tip", tip)
    f.add_joint(Joint("ab", "a", "tip", "b", "base", [Dof("T", (1, 0, 0), -0.2, 0.3), Dof("R", (0, 1, 1), -1, 1),
                                                      Dof("T", (0, 0, 1), -0.1, 0.1)]))
    f.add_joint(Joint("bc", "b", "tip", "c", "base", [Dof("R", (1, 2, 3), -2, 2)]))
    f.root = ("b", "base")  # "ab" is traversed up
    loc = np.eye(4)
    loc[:3, 3] = (0.5, 1.0, -0.25)
    f.location = loc
    return f


def _figures() -> list[Figure]:
    human = make_human("male", 50)
    rerooted = make_human("female", 5)
    rerooted.reroot("left_foot", "heel")  # legs, pelvis and spine traversed up
    return [human, rerooted, _slider()]


def _site_errors_mjcf(fig: Figure, model, data, frozen=()) -> float:
    for n, v in rx.joint_values(fig, frozen).items():
        data.qpos[model.joint(n).qposadr[0]] = v
    mujoco.mj_kinematics(model, data)
    worst = 0.0
    for name, _ in fig.iter_sites():
        T = fig.site_world(*name.split(".", 1))
        sid = model.site(name).id
        worst = max(worst, float(np.abs(data.site_xpos[sid] - T[:3, 3]).max()),
                    float(np.abs(data.site_xmat[sid].reshape(3, 3) - T[:3, :3]).max()))
    return worst


@pytest.mark.parametrize("index", range(3))
def test_mjcf_sites_match_fk(index: int) -> None:
    fig = _figures()[index]
    model = mujoco.MjModel.from_xml_string(rx.to_mjcf(fig))
    data = mujoco.MjData(model)
    assert model.nq == fig.ndof and model.nsite == sum(1 for _ in fig.iter_sites())
    rng = np.random.default_rng(index)
    for _ in range(5):
        fig.q = rng.uniform(fig.lower, fig.upper)
        assert _site_errors_mjcf(fig, model, data) <= TOL
    # limits: every MJCF joint range is the DOF's
    for j in fig.joints.values():
        for k, dof in enumerate(j.dofs):
            jid = model.joint(j.name if j.ndof == 1 else f"{j.name}.{k}").id
            assert model.jnt_limited[jid] and np.allclose(model.jnt_range[jid], (dof.lower, dof.upper), atol=0)


@pytest.mark.parametrize("index", range(3))
def test_urdf_sites_match_fk(index: int) -> None:
    fig = _figures()[index]
    urdf = yourdfpy.URDF.load(io.StringIO(rx.to_urdf(fig)))
    assert len(urdf.actuated_joint_names) == fig.ndof
    rng = np.random.default_rng(10 + index)
    for _ in range(3):
        fig.q = rng.uniform(fig.lower, fig.upper)
        urdf.update_cfg(rx.joint_values(fig))
        for name, _ in fig.iter_sites():
            T = fig.site_world(*name.split(".", 1))
            U = urdf.get_transform(name, "world")
            assert np.abs(U - T).max() <= TOL, name
    lim = {j.name: j.limit for j in urdf.robot.joints if j.limit is not None}
    for j in fig.joints.values():
        for k, dof in enumerate(j.dofs):
            got = lim[j.name if j.ndof == 1 else f"{j.name}.{k}"]
            assert (got.lower, got.upper) == (dof.lower, dof.upper)


def test_masses_and_inertias_carry_over() -> None:
    fig = make_human("male", 50)
    model = mujoco.MjModel.from_xml_string(rx.to_mjcf(fig))
    data = mujoco.MjData(model)
    massless = [s for s in fig.segments.values() if s.mass == 0]
    assert abs(model.body_subtreemass[1] - fig.total_mass - 1e-6 * len(massless)) < 1e-9
    fig.q = np.random.default_rng(3).uniform(fig.lower, fig.upper)
    for n, v in rx.joint_values(fig).items():
        data.qpos[model.joint(n).qposadr[0]] = v
    mujoco.mj_kinematics(model, data)
    mujoco.mj_comPos(model, data)
    com = data.subtree_com[1]
    assert np.abs(com - fig.centre_of_mass()).max() < 1e-7  # the massless floor moves it < 1e-7 m
    # an inertia tensor in a segment frame rotated into its body frame, eigenvalues unchanged
    seg = fig.segment("left_upper_arm")
    bid = model.body("left_upper_arm").id
    assert np.allclose(np.sort(model.body_inertia[bid]), np.sort(np.linalg.eigvalsh(seg.inertia)), rtol=1e-9)
    root = ET.fromstring(rx.to_urdf(fig))
    masses = {lk.get("name"): float(lk.find("inertial/mass").get("value")) for lk in root.iter("link")
              if lk.find("inertial") is not None}
    assert masses["left_upper_arm"] == seg.mass and len(masses) == len(fig.segments) - len(massless)


def test_floating_and_frozen() -> None:
    fig = make_human("male", 50)
    frozen = [j for j in fig.joints if "index" in j or "thumb" in j]
    model = mujoco.MjModel.from_xml_string(rx.to_mjcf(fig, floating=True, frozen=frozen))
    data = mujoco.MjData(model)
    nfrozen = sum(fig.joint(j).ndof for j in frozen)
    assert model.nv == fig.ndof - nfrozen + 6 and model.nq == model.nv + 1
    mujoco.mj_resetData(model, data)  # the free joint's qpos0 is the figure's location
    fig.q = np.random.default_rng(4).uniform(fig.lower, fig.upper) * 0.5
    model2 = mujoco.MjModel.from_xml_string(rx.to_mjcf(fig, floating=True, frozen=frozen))
    data2 = mujoco.MjData(model2)
    assert _site_errors_mjcf(fig, model2, data2, frozen) <= TOL


def test_cli_exports_both(tmp_path) -> None:
    urdf, xml = tmp_path / "h.urdf", tmp_path / "h.xml"
    assert main(["export-figure", "female:5", "-o", str(urdf)]) == 0
    assert main(["export-figure", "female:5", "-o", str(xml), "--floating"]) == 0
    assert yourdfpy.URDF.load(str(urdf)).robot.name == "female_p5"
    assert mujoco.MjModel.from_xml_path(str(xml)).nq == 137 + 7


def test_cli_bad_input(tmp_path, capsys) -> None:
    assert main(["export-figure", "male:50", "-o", str(tmp_path / "h.obj")]) == 2
    assert "unknown export format" in capsys.readouterr().err
    assert main(["export-figure", "male:50", "-o", str(tmp_path / "h.urdf"), "--floating"]) == 2
    assert main(["export-figure", "male:50", "-o", str(tmp_path / "h.xml"), "--freeze", "nope"]) == 2
    assert not list(tmp_path.iterdir())
