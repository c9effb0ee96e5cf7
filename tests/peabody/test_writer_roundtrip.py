"""Writing Peabody text: read -> write -> read gives the same figures; atomic writes."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from jackpy.atomic import atomic_write_text
from jackpy.errors import FigureError
from jackpy.peabody.compare import figure_differences
from jackpy.peabody.geometry import Psurf
from jackpy.peabody.groups import JointGroup, LinearDriver
from jackpy.peabody.model import Dof, Figure, Joint, Segment
from jackpy.peabody.notation import compose, decompose
from jackpy.peabody.reader import parse_figures, read_environment, read_figures
from jackpy.peabody.writer import figures_to_text, write_environment, write_figures

FIGURES = Path(__file__).resolve().parents[2] / "figures"
SHIPPED = sorted(FIGURES.glob("*.fig"))


def test_every_figure_ships() -> None:
    names = {p.stem for p in SHIPPED}
    assert {"table", "planar_arm", "arm7", "hexapod", "finger", "chair", "worktable"} <= names


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.name)
def test_shipped_figure_round_trips_in_place_and_elsewhere(path: Path, tmp_path: Path) -> None:
    figures = read_figures(path)
    same_dir = parse_figures(figures_to_text(figures), "again.fig")
    for a, b in zip(figures, same_dir, strict=True):
        assert figure_differences(a, b) == []
    out = tmp_path / "sub" / path.name
    out.parent.mkdir()
    write_figures(out, figures, source_dir=path.parent)
    moved = read_figures(out, allow_outside=True)  # psurf names rewritten, so the geometry still loads
    for a, b in zip(figures, moved, strict=True):
        assert figure_differences(a, b, dirs=(path.parent, out.parent)) == []
        assert all(s.psurf.mesh is not None for s in b.segments.values() if s.psurf)


def test_environment_round_trips(tmp_path: Path) -> None:
    env = read_environment(FIGURES / "workplace.env")
    out = tmp_path / "copy.env"
    write_environment(out, env, source_dir=FIGURES)
    text = out.read_text()
    assert 'include "' in text and "place chair at" in text and "figure crate {" in text
    back = read_environment(out, allow_outside=True)  # (its includes stay in figures/)
    assert back.outside and all(str(FIGURES) in p for p in back.outside)
    assert list(back.figures) == list(env.figures)
    for name, fig in env.figures.items():
        assert figure_differences(fig, back.figures[name], dirs=(FIGURES, tmp_path)) == []


def _random_rigid(rng: np.random.Generator) -> np.ndarray:
    m = np.eye(4)
    m[:3, :3] = Rotation.random(random_state=rng).as_matrix()
    m[:3, 3] = rng.normal(scale=0.5, size=3)
    return m


def test_arbitrary_figure_round_trips() -> None:
    rng = np.random.default_rng(7)
    fig = Figure("random")
    shear = np.eye(4)
    shear[0, 1] = 0.3
    for k in range(4):
        psurf = Psurf("box.pss", [_random_rigid(rng) @ np.diag([2.0, -1.0, 0.5, 1.0]), shear, np.eye(4), ][k % 3])
        s = fig.add_segment(Segment(f"s{k}", psurf=psurf if k < 3 else None, attribute=None if k else "odd name",
                                    mass=float(k), com=rng.normal(size=3) * 0.1,
                                    inertia=np.diag(rng.uniform(0.01, 0.1, 3)) + 0.001))
        s.add_site("in", _random_rigid(rng))
        s.add_site("out", _random_rigid(rng))
        if k:
            dofs = [Dof("R", rng.normal(size=3), -1.0, 2.0), Dof("T", np.array([0.0, 1.0, 0.0]), -0.2, 0.3)]
            fig.add_joint(Joint(f"j{k}", f"s{k - 1}", "out", f"s{k}", "in", dofs, np.array([0.5, -0.1])))
    fig.add_group(JointGroup("g", ["j2", "j3"], ["a", "b"], LinearDriver(rng.uniform(-1, 1, (4, 2)) * 0.1,
                                                                         np.array([0.1, 0.0, 0.2, 0.01])),
                             lower=[-1.0, -1.0], upper=[1.0, 1.0], A=[[1.0, -2.0]], b=[0.5], angles=[0.2, 0.1]))
    fig.root = ("s1", "out")
    fig.location = _random_rigid(rng)
    back = parse_figures(figures_to_text([fig]))[0]
    assert figure_differences(fig, back) == []


@settings(max_examples=200, deadline=None)
@given(st.integers(0, 2**32 - 1), st.sampled_from(["rigid", "scaled", "near_pi", "axis"]))
def test_decompose_composes_back(seed: int, kind: str) -> None:
    rng = np.random.default_rng(seed)
    m = _random_rigid(rng)
    if kind == "scaled":
        m = m @ np.diag([*rng.uniform(-3, 3, 3), 1.0])
    elif kind == "near_pi":
        axis = rng.normal(size=3)
        m[:3, :3] = Rotation.from_rotvec(axis / np.linalg.norm(axis) * (np.pi - rng.uniform(0, 1e-7))).as_matrix()
    elif kind == "axis":
        m[:3, :3] = Rotation.from_euler("y", rng.uniform(-360, 360), degrees=True).as_matrix()
    prims = decompose(m)
    np.testing.assert_allclose(compose(prims), m, atol=1e-10)
    from jackpy.peabody.notation import fmt, prim_matrix

    rounded = [(n, tuple(float(fmt(a)) for a in args)) for n, args in prims]  # what the file holds
    np.testing.assert_allclose(compose(rounded), m, atol=1e-9)
    assert all(prim_matrix(p).shape == (4, 4) for p in prims)


def test_unwritable_names_are_refused() -> None:
    fig = Figure("bad name")
    fig.add_segment(Segment("a"))
    with pytest.raises(FigureError, match="Peabody names"):
        figures_to_text([fig])


def test_atomic_write_keeps_old_file_on_failure(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    target = tmp_path / "keep.fig"
    target.write_text("old")
    os.chmod(target, 0o640)

    def boom(*_args: object) -> None:
        raise OSError("disk full")

    monkeypatch.setattr(os, "replace", boom)
    with pytest.raises(OSError, match="disk full"):
        atomic_write_text(target, "new")
    monkeypatch.undo()
    assert target.read_text() == "old" and os.listdir(tmp_path) == ["keep.fig"]
    atomic_write_text(target, "new")
    assert target.read_text() == "new" and (target.stat().st_mode & 0o777) == 0o640
    assert os.listdir(tmp_path) == ["keep.fig"]
