"""Sessions: save and reopen (exact posture, goals, settings), recovery, malformed sidecars."""

import json

import numpy as np
import pytest

from jackpy.errors import SessionError
from jackpy.ui import session
from jackpy.ui.app import App


def posed_app() -> App:
    env, base = session.default_scene()
    app = App(env)
    app.scene_dir = base
    fig = app.figure_of_interest()
    rng = np.random.default_rng(3)
    fig.q = np.clip(rng.normal(0.0, 0.3, fig.ndof), fig.lower, fig.upper)
    for side in ("left", "right"):  # the forearm twist joints move together (a linear group)
        fig.groups[f"{side}_forearm"].set_angles(fig, np.array([0.3]))
    g = app.ensure_goal(fig, "right_palm.palm_centre", "position")
    g.weight, g.priority, g.chain = 2.5, 1, "right_shoulder"
    app.settings.literal_grab = True
    app.camera.yaw = 0.4
    return app


def test_save_and_reopen_restores_posture_goals_and_settings(tmp_path):
    app = posed_app()
    path = tmp_path / "nested" / "scene.env"
    session.save_session(app, path)
    assert path.is_file() and session.sidecar_path(path).is_file()
    assert app.session_path == path and not app.dirty
    other = App(session.default_scene()[0])
    session.open_session(other, path)
    for name, fig in app.env.figures.items():
        assert np.array_equal(other.env.figure(name).q, fig.q)
        assert np.array_equal(other.env.figure(name).location, fig.location)
    assert [g.key for g in other.goals] == [g.key for g in app.goals]
    g = other.goal(f"{app.figure_of_interest().name}:right_palm.palm_centre")
    assert (g.weight, g.priority, g.chain) == (2.5, 1, "right_shoulder")
    # the generated human comes back as the standard human: groups, body specification, behaviors
    human = other.figure_of_interest()
    assert "spine" in human.groups and human.body_spec.percentile == 50 and human.name in other.loops
    assert other.settings.literal_grab and other.camera.yaw == pytest.approx(0.4)
    # the .env alone (without the sidecar) also carries the posture, to its text precision
    session.sidecar_path(path).unlink()
    env, data = session.load_session(path)
    assert data is None
    fig = app.figure_of_interest()
    assert np.allclose(env.figure(fig.name).q, fig.q, atol=1e-6)


def test_save_leaves_no_temporary_files(tmp_path):
    session.save_session(posed_app(), tmp_path / "a.env")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.env", "a.jackpy.json", "a_psurf"]
    # the generated human's surfaces, one file per segment, nothing half-written
    files = sorted(p.name for p in (tmp_path / "a_psurf" / "male_p50").iterdir())
    assert len(files) == sum(s.psurf is not None for s in posed_app().figure_of_interest().segments.values())
    assert all(f.endswith(".pss") for f in files)


def test_malformed_sidecar_is_a_session_error(tmp_path):
    app = posed_app()
    path = tmp_path / "s.env"
    session.save_session(app, path)
    session.sidecar_path(path).write_text("{not json")
    with pytest.raises(SessionError, match="sidecar"):
        session.load_session(path)
    data = session.session_dict(app)
    data["figures"][app.figure_of_interest().name]["q"] = [0.0]
    session.sidecar_path(path).write_text(json.dumps(data))
    with pytest.raises(SessionError, match="q"):
        session.load_session(path)
    with pytest.raises(SessionError, match="no such"):
        session.load_session(tmp_path / "missing.env")


def test_autosave_recover_and_discard(tmp_path, monkeypatch):
    monkeypatch.setenv("JACKPY_HOME", str(tmp_path / "home"))
    assert session.pending_recovery() is None
    app = posed_app()
    session.autosave(app)
    assert app.session_path is None  # autosave does not take over the user's file
    found = session.pending_recovery()
    assert found is not None
    other = App(session.default_scene()[0])
    session.recover(other, found)
    name = app.figure_of_interest().name
    assert np.array_equal(other.env.figure(name).q, app.env.figure(name).q)
    assert other.session_path is None and other.dirty
    assert session.pending_recovery() is None


def test_user_goal_with_behaviors_survives_save_and_open(tmp_path):
    env, base = session.default_scene()
    app = App(env)
    app.scene_dir = base
    fig = app.figure_of_interest()
    g = app.add_goal(fig, "right_upper_arm.elbow", "half-space")
    g.axis = np.array([1.0, 0.0, 0.0])
    g.weight, g.priority = 3.0, 1
    app.step()
    assert app.user_goal_part(g.key) == "right"
    session.save_session(app, tmp_path / "u.env")
    other = App(session.default_scene()[0])
    session.open_session(other, tmp_path / "u.env")
    h = other.goal(g.key)
    assert h.kind == "half-space" and np.array_equal(h.axis, g.axis) and (h.weight, h.priority) == (3.0, 1)
    other.needs_solve = True
    other.step()
    loop = other.loops[fig.name]
    u = loop.user_goal(g.key)
    assert u.enabled and u.level == 1 and u.goal.weight == 3.0 and u.part == "right"
