"""``jackpy task``: writes a motion file the motion module reads and the timing table; a
malformed script is one line FILE:LINE:COL: expected ..., exit 2."""

import csv

from jackpy.cli import main
from jackpy.motion import motion_file
from jackpy.tasks import fitts


def test_task_command_writes_motion_and_table(tmp_path, panel_scene, capsys):
    script = tmp_path / "s.task"
    script.write_text("Jane is a 50 percentile female.\nJane, look at twf-3.\nJane, turn twf-3 to state 3.\n")
    out, table = tmp_path / "out.motion.json", tmp_path / "t.csv"
    rc = main(["task", str(script), "--scene", str(panel_scene), "-o", str(out), "--table", str(table)])
    text = capsys.readouterr().out
    assert rc == 0, text
    assert "control ctrlpanel.twf_3: 3" in text
    mf = motion_file.load(out)
    assert mf.timeline.figures() == ["Jane"] and mf.timeline.cast["Jane"]["human"] == "female:50"
    rows = list(csv.DictReader(table.open()))
    assert rows[0]["actor"] == "Jane" and rows[0]["action"] == "Look twf-3" and rows[0]["limb"] == "head"
    assert list(rows[0]) == fitts.TABLE_COLUMNS
    kinds = [m.kind for m in mf.timeline.motions]
    assert kinds[0] == "gaze" and "arm" in kinds
    # the motion file plays on the scene alone (no task knowledge base): bake it coarsely
    from jackpy.motion import cast
    from jackpy.motion.bake import Baker

    env, loops = cast.build(mf.timeline, scene=panel_scene)
    frames = Baker(mf.timeline, loops, env, fps=2).bake()
    assert len(frames) == int(mf.timeline.duration * 2) + 1


def test_malformed_script_one_line_exit_2(tmp_path, capsys):
    script = tmp_path / "bad.task"
    script.write_text("John is a 50 percentile male.\nJohn, look twf-1.\n")
    rc = main(["task", str(script), "-o", str(tmp_path / "o.motion.json")])
    err = capsys.readouterr().err.strip()
    assert rc == 2
    assert err.endswith(f"{script}:2:12: expected 'at', found 'twf-1'") and "\n" not in err
    assert not (tmp_path / "o.motion.json").exists()


def test_failed_command_exit_1(tmp_path, panel_scene, capsys):
    script = tmp_path / "w.task"
    script.write_text("John is a 50 percentile male.\nJohn, walk to the door.\n")
    rc = main(["task", str(script), "--scene", str(panel_scene), "-o", str(tmp_path / "o.motion.json")])
    err = capsys.readouterr().err
    assert rc == 1 and "nothing in the scene is called 'door'" in err and f"{script}:2" in err
