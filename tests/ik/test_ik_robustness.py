"""The robustness mix (bench row ``ik-robustness`` runs 10,000): no NaN, no limit violated, no exception."""

from jackpy.bench.cases_ik_robustness import run_mix


def test_random_problems_stay_finite_feasible_and_raise_nothing() -> None:
    out = run_mix(60, seed=11)
    assert out["exceptions"] == 0, out["errors"]
    assert out["nan"] == 0 and out["violations"] == 0, out["worst_violation"]
