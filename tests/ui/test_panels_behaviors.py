"""Behaviors, Figure and Import logic behind the panels (no window): behavior switches and
parameters from their descriptions, plain-IK fallback, rescale in place, CAD import with units."""

import numpy as np
import pytest
import trimesh

from jackpy.behaviors import describe
from jackpy.scene.cad import CADObject
from jackpy.ui import session
from jackpy.ui.app import App
from jackpy.ui.panels.behaviors import from_display, set_enabled, set_param, to_display


def make_app() -> App:
    env, base = session.default_scene()
    app = App(env)
    app.scene_dir = base
    return app


def test_behavior_params_shown_in_their_units_and_validated():
    app = make_app()
    loop = app.loops[app.figure_of_interest().name]
    names = [b.name for b in loop.behaviors]
    assert {"feet", "balance", "stepping", "hands", "gaze"} <= set(names)
    hands = loop.behavior("hands")
    spec = next(s for s in describe(hands.params) if s.name == "max_turn")
    assert spec.unit == "deg" and to_display(spec, spec.value) == pytest.approx(10.0)
    assert from_display(spec, 20.0) == pytest.approx(np.radians(20.0))
    assert set_param(app, hands, "max_turn", np.radians(20.0)) and hands.params.max_turn == pytest.approx(np.radians(20))
    assert app.needs_solve
    assert not set_param(app, hands, "max_turn", 10.0)  # outside its range: refused, logged, kept
    assert hands.params.max_turn == pytest.approx(np.radians(20)) and app.log[-1].startswith("error")
    set_enabled(app, loop.behavior("stepping"), False)
    assert not loop.behavior("stepping").enabled


def test_behavior_settings_survive_save_and_open(tmp_path):
    app = make_app()
    loop = app.loops[app.figure_of_interest().name]
    loop.behavior("stepping").enabled = False
    set_param(app, loop.behavior("hands"), "lean_rate", 0.02)
    session.save_session(app, tmp_path / "s.env")
    other = make_app()
    session.open_session(other, tmp_path / "s.env")
    loop2 = other.loops[other.figure_of_interest().name]
    assert not loop2.behavior("stepping").enabled
    assert loop2.behavior("hands").params.lean_rate == pytest.approx(0.02)


def test_switching_to_plain_ik_and_back():
    app = make_app()
    app.set_behaviors_enabled(False)
    assert not app.settings.behaviors and app.behavior_figures() == set()
    app.set_behaviors_enabled(True)
    assert app.behavior_figures() == {app.figure_of_interest().name}


def test_rescale_in_place_keeps_posture_and_is_one_undo_step():
    app = make_app()
    fig = app.figure_of_interest()
    q0, stature0 = fig.q.copy(), fig.body_spec.stature
    app.rescale_figure(fig.name, "female", 5)
    fig = app.env.figure(fig.name)
    assert fig.body_spec.sex == "female" and fig.body_spec.stature < stature0 - 0.1
    assert app.needs_solve and app.undo_stack.undo_label.startswith("rescale")
    feet = {s: fig.site_world(f"{s}_foot", "ball")[1, 3] for s in ("left", "right")}
    assert all(abs(h) < 1e-6 for h in feet.values())  # still on the floor
    for _ in range(40):
        if not app.needs_solve:
            break
        app.step()
    assert all(abs(fig.site_world(f"{s}_foot", "ball")[1, 3]) < 1e-4 for s in feet)
    app.undo()
    fig = app.env.figure(fig.name)
    assert fig.body_spec.sex == "male" and np.array_equal(fig.q, q0) and app.loops[fig.name].figure is fig
    app.rescale_figure(fig.name, "female", 150)  # a bad percentile: logged, nothing changed
    assert app.log[-1].startswith("error") and app.env.figure(fig.name).body_spec.sex == "male"


def test_import_cad_units_up_errors_and_undo(tmp_path):
    app = make_app()
    trimesh.creation.box((1000.0, 500.0, 200.0)).export(tmp_path / "box.stl")  # mm, z up
    names = list(app.env.figures)
    assert app.import_cad(tmp_path / "box.stl", "mm", "z")
    obj = app.env.figures["box"]
    lo, hi = obj.display_mesh().vertices.min(axis=0), obj.display_mesh().vertices.max(axis=0)
    assert np.allclose(np.sort(hi - lo), [0.2, 0.5, 1.0], atol=1e-6)
    assert (hi - lo)[1] == pytest.approx(0.2)  # file z (0.2 m) is up
    assert isinstance(app.env.figures["box"], CADObject) and app.undo_stack.undo_label.startswith("import")
    (tmp_path / "bad.stl").write_text("not an stl")
    for path, units in ((tmp_path / "bad.stl", "mm"), (tmp_path / "missing.obj", "m"), (tmp_path / "box.stl", "ft")):
        assert not app.import_cad(path, units, "y")
        assert app.log[-1].startswith("error: import")
    assert list(app.env.figures) == names + ["box"]
    app.undo()
    assert list(app.env.figures) == names
    app.redo()
    assert "box" in app.env.figures


def test_behavior_toggle_and_parameter_changes_are_one_undo_step_each():
    from jackpy.ui.panels.behaviors import begin_param_drag, change_param, end_param_drag

    app = make_app()
    loop = app.loops[app.figure_of_interest().name]
    stepping, hands = loop.behavior("stepping"), loop.behavior("hands")
    depth = len(app.undo_stack._undo)
    set_enabled(app, stepping, False)
    assert not stepping.enabled and len(app.undo_stack._undo) == depth + 1
    rate0 = hands.params.lean_rate
    begin_param_drag(app)  # a slider drag: many values, one step
    for v in (0.012, 0.015, 0.02):
        assert set_param(app, hands, "lean_rate", v)
    end_param_drag(app, hands, "lean_rate")
    assert len(app.undo_stack._undo) == depth + 2
    assert change_param(app, hands, "orientation_rules", not hands.params.orientation_rules)
    assert not change_param(app, hands, "max_turn", 10.0)  # refused: no step
    assert len(app.undo_stack._undo) == depth + 3
    app.undo()
    hands = app.loops[app.figure_of_interest().name].behavior("hands")
    assert hands.params.orientation_rules and hands.params.lean_rate == pytest.approx(0.02)
    app.undo()
    assert hands.params.lean_rate == pytest.approx(rate0)
    assert not stepping.enabled
    app.undo()
    assert stepping.enabled
    app.redo()
    assert not stepping.enabled
