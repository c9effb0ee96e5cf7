"""A saved human stays a human (issue 19 item 9): ``jackpy human -o f.fig`` then reading it back
gives the same figure -- segments, sites, joints, the spine and shoulder groups with their drivers,
the body specification -- the same FK at random postures, and behaviors run on it; an ``.env``
that includes human figures gives humans too."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from jackpy.behaviors import BehaviorLoop, manipulation
from jackpy.behaviors.anatomy import human_anatomy
from jackpy.body.human import make_human, peabody_copy
from jackpy.body.saved import is_standard_human, restore_human, restore_humans
from jackpy.commands.human import write_human
from jackpy.errors import FigureError
from jackpy.peabody.compare import figure_differences
from jackpy.peabody.groups import VariableMap
from jackpy.peabody.reader import parse_figures, read_environment, read_figures
from jackpy.peabody.writer import figures_to_text


@pytest.fixture(scope="module")
def saved(tmp_path_factory) -> dict[tuple[str, int], tuple[object, object]]:
    """(sex, percentile) -> (the generated human, the figure read back from its .fig)."""
    out = {}
    folder = tmp_path_factory.mktemp("humans")
    for sex in ("female", "male"):
        for p in (5, 50, 95):
            fig = make_human(sex, p)
            path = folder / f"{sex}_{p}.fig"
            write_human(path, fig)
            back = read_figures(path)[0]
            assert restore_human(back)
            out[(sex, p)] = (fig, back, path)
    return out


@pytest.mark.parametrize("sex", ["female", "male"])
@pytest.mark.parametrize("p", [5, 50, 95])
def test_every_standard_human_reads_back_equal(saved, sex: str, p: int) -> None:
    fig, back, path = saved[(sex, p)]
    assert figure_differences(peabody_copy(fig, f"{path.stem}_psurf"), back) == []
    assert list(back.groups) == list(fig.groups)
    assert back.body_spec == fig.body_spec and is_standard_human(back)
    assert all(s.psurf.mesh is not None for s in back.segments.values() if s.psurf)
    # the same FK at random postures of the free variables (group angles included)
    rng = np.random.default_rng(p)
    vm_a, vm_b = VariableMap(fig), VariableMap(back)
    assert vm_a.names == vm_b.names
    for _ in range(5):
        x = rng.uniform(vm_a.lower, vm_a.upper)
        vm_a.apply(x)
        vm_b.apply(x)
        wa, wb = fig.world_transforms(), back.world_transforms()
        for name in wa:
            np.testing.assert_allclose(wa[name], wb[name], atol=1e-9)


def _drive(fig) -> np.ndarray:
    """Reach far forward with the right hand for 12 frames of the behavior loop; the final q."""
    loop = BehaviorLoop(fig, human_anatomy(fig))
    palm = fig.site_world(*loop.anatomy.hands["right"].palm)[:3, 3].copy()
    for i in range(12):
        manipulation.move_hand(loop, "right", position=palm + np.array([0.0, 0.0, 0.05 * i]))
        loop.step()
    assert {"balance", "stepping"} <= {b.name for b in loop.behaviors}
    return fig.q


def test_behaviors_balance_and_stepping_run_on_a_read_back_human_as_on_the_original(saved) -> None:
    _, _, path = saved[("female", 5)]
    back = read_figures(path)[0]  # (fresh: the FK test moved the module's copies)
    restore_human(back)
    q_back, q_orig = _drive(back), _drive(make_human("female", 5))
    assert np.all(np.isfinite(q_back)) and np.abs(q_back - back.q).max() == 0
    np.testing.assert_allclose(q_back, q_orig, atol=1e-6)


def test_an_environment_including_humans_gives_humans(saved, tmp_path: Path) -> None:
    _, _, path = saved[("male", 50)]
    folder = path.parent
    (folder / "scene.env").write_text(f'include "{path.name}";\nplace male_p50 at trans(100cm,0cm,0cm);\n')
    env = read_environment(folder / "scene.env")
    assert restore_humans(env) == ["male_p50"]
    fig = env.figures["male_p50"]
    assert is_standard_human(fig) and fig.body_spec.percentile == 50
    BehaviorLoop(fig, human_anatomy(fig)).step()


def test_a_marker_without_the_human_groups_is_refused() -> None:
    text = ('figure f { human { population = "ansur2"; sex = "female"; percentile = 50; }'
            ' segment a { } }')
    fig = parse_figures(text, "m.fig")[0]
    assert fig.human is not None and fig.human.percentile == 50
    assert not is_standard_human(fig)
    with pytest.raises(FigureError, match="lacks its spine and shoulder groups"):
        restore_human(fig)
    again = parse_figures(figures_to_text([fig]), "again.fig")[0]
    assert again.human == fig.human


def test_the_human_marker_is_compared_within_tolerance() -> None:
    """The marker's numbers agree within ``tol`` like every other number (a rounding difference in
    the generated mass is no difference); its names, and a real change, are differences."""
    import copy
    import dataclasses

    a = peabody_copy(make_human("female", 5), "female_p5_psurf")
    b = copy.deepcopy(a)
    b.human = dataclasses.replace(a.human, mass=a.human.mass * (1 + 1e-15))
    assert figure_differences(a, b, tol=1e-7) == []
    b.human = dataclasses.replace(a.human, mass=a.human.mass + 0.5)
    assert figure_differences(a, b, tol=1e-7) == [f"human mass: {a.human.mass} != {a.human.mass + 0.5}"]
    b.human = dataclasses.replace(a.human, sex="male")
    assert len(figure_differences(a, b, tol=1e-7)) == 1
    b.human = dataclasses.replace(a.human, dims={**a.human.dims, "thigh.length": a.human.dims["thigh.length"] + 0.01})
    assert figure_differences(a, b, tol=1e-7)[0].startswith("human dims")
