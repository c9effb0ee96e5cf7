"""Strength-guided lifting outputs: the baked motion, the PNG plot and the ``jackpy lift`` command."""

from __future__ import annotations

import io
import json
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from jackpy.body.human import make_human
from jackpy.cli import main
from jackpy.motion import motion_file
from jackpy.planning.lifting import LiftTask, figure_offset, overhead_task, shoulder_position, strength_guided_lift
from jackpy.planning.lifting_motion import lift_motion, sample_times
from jackpy.planning.lifting_plot import LOAD_COLOURS, lift_plot_png


@pytest.fixture(scope="module")
def figure():
    return make_human("male", 50)


@pytest.fixture(scope="module")
def light(figure):
    return strength_guided_lift(figure, overhead_task(figure, 3.0))


def test_baked_motion_follows_the_lift(figure, light, tmp_path: Path) -> None:
    mf = lift_motion(figure, light, fps=30.0, human="male:50")
    baked = mf.baked[figure.name]
    assert baked.n_frames == len(sample_times(light, 30.0)) == int(np.ceil(light.frames[-1].t * 30.0 - 1e-9)) + 1
    np.testing.assert_allclose(baked.q[0], light.frames[0].q)
    np.testing.assert_allclose(baked.q[-1], light.frames[-1].q)
    path = tmp_path / "lift.motion.json"
    motion_file.save(mf, path)
    back = motion_file.load(path)
    np.testing.assert_array_equal(back.baked[figure.name].q, baked.q)
    # the played-back grip stays on the lift's path (interpolation between steps of <= 2 degrees)
    f = make_human("male", 50)
    path_pts = light.hand_path
    for i in range(0, baked.n_frames, 5):
        baked.posture(f, i).apply_to(f)
        grip = f.site_world("right_palm", "grip")[:3, 3]
        assert np.min(np.linalg.norm(path_pts - grip, axis=1)) < 0.01


def test_plot_draws_every_load(figure, light) -> None:
    heavy = strength_guided_lift(figure, overhead_task(figure, 9.0))
    png = lift_plot_png(figure, [light, heavy])
    img = np.asarray(Image.open(io.BytesIO(png)).convert("RGB"))
    assert img.shape == (520, 3 * 520, 3)
    side = img[:, :520].reshape(-1, 3)
    for colour in LOAD_COLOURS[:2]:
        assert np.any(np.all(side == colour, axis=1)), colour


def test_figure_offsets_are_in_the_figure_frame(figure) -> None:
    sh = shoulder_position(figure)
    np.testing.assert_allclose(figure_offset(figure, [0.0, 0.1, 0.3]), sh + [0.0, 0.1, 0.3])
    task = overhead_task(figure, 1.0)
    assert task.goal[1] > sh[1] + 0.3 and task.start[1] < sh[1]


def test_cli_writes_summary_plot_and_motion(tmp_path: Path, capsys) -> None:
    out = tmp_path / "out"
    rc = main(["lift", "--load", "8lb", "--compare", "2", "-o", str(out)])
    assert rc == 0, capsys.readouterr()
    summary = json.loads((out / "lift.json").read_text())
    assert summary["reached"] and summary["task"]["load_kg"] == pytest.approx(8 * 0.45359237)
    assert summary["compare"][0]["load_kg"] == 2.0
    assert len(summary["series"]["t_s"]) == summary["iterations"] + 1
    assert set(summary["series"]["ratios"]) == {"shoulder", "elbow", "waist"}
    Image.open(out / "lift.png").verify()
    assert motion_file.load(out / "lift.motion.json").n_frames > 2
    assert "reached the goal" in capsys.readouterr().out


def test_cli_goal_out_of_reach_exits_1(tmp_path: Path, capsys) -> None:
    rc = main(["lift", "--load", "1", "--goal", "0", "3.5", "0.3", "--compare", "-o", str(tmp_path / "o")])
    assert rc == 1
    assert "short" in capsys.readouterr().out
    assert not json.loads((tmp_path / "o" / "lift.json").read_text())["reached"]


@pytest.mark.parametrize("argv", [["--load", "heavy"], ["--load", "5", "--comfort", "0"],
                                  ["--load", "5", "--exertion", "2"], ["--load", "5", "--goal", "1", "2"],
                                  ["--load", "5", "--goal", "1", "nan", "0"]])
def test_cli_bad_input_exits_2(tmp_path: Path, capsys, argv) -> None:
    with pytest.raises(SystemExit) as e:
        main(["lift", *argv, "-o", str(tmp_path / "o")])
    assert e.value.code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err[-1].startswith("jackpy lift: error:")


def test_cli_start_out_of_reach_is_one_line(tmp_path: Path, capsys) -> None:
    assert main(["lift", "--load", "1", "--start", "0", "0.2", "1.5", "-o", str(tmp_path / "o")]) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "out of the arm's reach" in err[0]
    assert not (tmp_path / "o" / "lift.json").exists()


def test_cli_output_that_is_a_file_is_refused(tmp_path: Path, capsys) -> None:
    f = tmp_path / "taken"
    f.write_text("mine")
    assert main(["lift", "--load", "1", "-o", str(f)]) == 1
    assert f.read_text() == "mine"
    assert len(capsys.readouterr().err.strip().splitlines()) == 1


def test_task_needs_finite_goal() -> None:
    with pytest.raises(ValueError):
        LiftTask(1.0, [0.0, np.inf, 0.0])


EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "workplace" / "workplace.json"


def test_cli_lifts_to_a_site_of_a_scene(tmp_path: Path, capsys) -> None:
    from jackpy.scene.workplace import load_workplace, resolve_target

    rc = main(["lift", str(EXAMPLE), "--load", "3", "--to", "shelf.box_handle", "--compare", "-o", str(tmp_path)])
    assert rc == 0, capsys.readouterr()
    summary = json.loads((tmp_path / "lift.json").read_text())
    target = resolve_target(load_workplace(EXAMPLE).env, "shelf.box_handle")[1]
    np.testing.assert_allclose(summary["task"]["goal_m"], target)
    assert np.linalg.norm(np.array(summary["series"]["hand_m"][-1]) - target) <= 0.01


@pytest.mark.parametrize("argv, contains", [(["{scene}", "--to", "shelf.nothing"], "no site"),
                                            (["--to", "shelf.box_handle"], "give the SCENE"),
                                            (["{d}/missing.json"], "no such scene")])
def test_cli_scene_errors_are_one_line(tmp_path: Path, capsys, argv, contains) -> None:
    argv = [a.format(scene=EXAMPLE, d=tmp_path) for a in argv]
    assert main(["lift", *argv, "--load", "3", "-o", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and contains in err[0]
