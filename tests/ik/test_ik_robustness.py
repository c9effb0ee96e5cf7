"""The robustness mix (bench row ``ik-robustness`` runs 10,000): no NaN, no limit violated, no exception."""

import numpy as np

from jackpy import ik
from jackpy.bench.cases_ik_robustness import TOL, _random_problem, figures, run_mix, violation
from jackpy.peabody.groups import VariableMap


def test_random_problems_stay_finite_feasible_and_raise_nothing() -> None:
    out = run_mix(60, seed=11)
    assert out["exceptions"] == 0, out["errors"]
    assert out["nan"] == 0 and out["violations"] == 0, out["worst_violation"]


def _mix_problem(index: int, seed: int = 0):
    """Problem ``index`` of ``run_mix(n, seed)`` (the draws do not depend on the solves)."""
    rng = np.random.default_rng(seed)
    figs = figures()
    starts = {id(f): VariableMap(f).x() for f, _ in figs}
    for k in range(index + 1):
        fig, sites = figs[k % len(figs)]
        p = _random_problem(fig, sites, starts[id(fig)], rng, False)
    return fig, p


def test_a_near_singular_aim_keeps_the_step_factor_positive_definite() -> None:
    """Problem 672 of the 10,000 mix (seed 0), one level on the chain: an ``Aim`` whose site nearly
    touches its point has a Jacobian of |J|_F^2 ~ 2e18, and a restart's damping (0.3 x 1e-4) was
    below the rounding of ``J J^T``: the box step's Cholesky factor raised. The damping is now at
    least ``1e-12 |J|_F^2``."""
    fig, p = _mix_problem(672)
    assert [type(g).__name__ for g in p.goals] == ["Aim", "Orientation", "Plane"]
    r = ik.solve(p, max_iterations=100)
    assert np.all(np.isfinite(r.q)) and violation(fig) <= TOL


def test_a_priority_step_stays_on_its_active_row() -> None:
    """Problem 3909 of the 10,000 mix (seed 0): two levels on the chain, the group row active. The
    book step's direction, projected onto the row and the held level's rows together, kept a part
    across the row: a trial left it by 2.9e-8. The direction is now exactly along the active rows."""
    fig, p = _mix_problem(3909)
    assert sorted({p.level_of(g) for g in p.goals}) == [0, 1]
    ik.solve(p, max_iterations=100)
    assert violation(fig) <= TOL
