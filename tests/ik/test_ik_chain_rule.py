"""The compiled chain rule to the scaled variables (``ik/chain_rule.py``) equals the numpy reference."""

import numpy as np
import pytest

from jackpy import ik
from jackpy.bench import cases_ik
from jackpy.ik.chain_rule import to_z
from jackpy.ik.problem import Compiled
from jackpy.peabody.groups import VariableMap


@pytest.mark.skipif(to_z is None, reason="numba not installed")
def test_compiled_chain_rule_matches_numpy() -> None:
    fig, problem, goals = cases_ik.human_problem()
    problem.set_scale("left_shoulder_complex", [0.5, 1.0, 0.25])  # scaled group angles
    problem.lock("right_elbow")
    rng = np.random.default_rng(4)
    vm = VariableMap(fig)
    for _ in range(5):
        cases_ik.set_human_targets(fig, goals, cases_ik.human_posture(fig, rng, 0.8))
        vm.apply(cases_ik.human_posture(fig, rng, 0.8))
        problem.invalidate()
        comp = problem.compile()
        assert comp._blocks  # the standard human has groups
        x, z, _, _ = comp.start()
        fast = comp.evaluate(x, fig.q, z)
        comp._geometry = None
        try:
            Compiled.compiled_chain = False
            slow = comp.evaluate(x, fig.q, z)
        finally:
            Compiled.compiled_chain = True
        for lv in fast.levels:
            assert np.allclose(fast.levels[lv][1], slow.levels[lv][1], rtol=0, atol=1e-13)
            assert np.array_equal(fast.levels[lv][0], slow.levels[lv][0])


def test_weighted_goals_keep_their_weights() -> None:
    fig, problem, goals = cases_ik.human_problem()
    comp = problem.compile()
    x, z, _, _ = comp.start()
    one = comp.evaluate(x, fig.q, z)
    goals[1].weight = 4.0
    two = comp.evaluate(x, fig.q, z)
    F1, J1 = one.levels[0]
    F2, J2 = two.levels[0]
    rows = slice(9, 18)  # the second goal's rows (9 per frame goal)
    assert np.allclose(F2[rows], 2.0 * F1[rows]) and np.allclose(J2[rows], 2.0 * J1[rows])
    assert np.array_equal(F2[:9], F1[:9]) and np.array_equal(J2[:9], J1[:9])
    assert isinstance(ik.solve(problem, apply=False).status, str)
