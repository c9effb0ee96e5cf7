"""The compiled spine distribution equals the numpy reference (value and analytic derivative)."""

import numpy as np
import pytest

from jackpy.body import spine_kernel
from jackpy.body.spine import SPINE_ANGLES, SPINE_DOFS, SpineDriver, SpineWeights, distribute_with_derivative

FLAVOURS = [None, SpineWeights(initiator=17),
            SpineWeights(bottom=3, top=14, initiator=8, resistor=12, resistance=0.7, spread=2.5),
            SpineWeights(initiator=5, resistor=2, resistance=0.4)]


def reference(driver: SpineDriver, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The driver's model axis by axis with the numpy :func:`distribute_with_derivative`."""
    out = driver.rest.copy()
    jac = np.zeros(out.shape + (3,))
    for c, (a, t) in enumerate(zip(SPINE_ANGLES, theta)):
        k = SPINE_DOFS.index(a)
        rest = driver.rest[:, k]
        out[:, k], jac[:, k, c] = distribute_with_derivative(rest, rest, driver.lower[:, k], driver.upper[:, k],
                                                             float(t), driver.weights)
    return out.reshape(-1), jac.reshape(-1, 3)


@pytest.mark.skipif(not spine_kernel.AVAILABLE, reason="numba not installed")
@pytest.mark.parametrize("weights", FLAVOURS)
def test_kernel_matches_reference(weights: SpineWeights | None) -> None:
    driver = SpineDriver(weights)
    lo, hi = driver.group_limits()
    rng = np.random.default_rng(7)
    thetas = [np.zeros(3), lo - 0.2, hi + 0.2] + [rng.uniform(lo - 0.1, hi + 0.1) for _ in range(200)]
    thetas += [np.array([t[0], 0.0, t[2]]) for t in thetas[3:40]]  # one axis exactly at rest (the kink)
    for theta in thetas:
        out, jac = driver.evaluate(theta)  # the compiled path
        ref_out, ref_jac = reference(driver, theta)
        assert np.allclose(out, ref_out, rtol=0, atol=1e-13)
        assert np.allclose(jac, ref_jac, rtol=0, atol=1e-12)


def test_driver_uses_the_kernel_when_numba_is_there() -> None:
    from jackpy import compiled

    assert spine_kernel.AVAILABLE == (compiled.numba is not None) and (spine_kernel._spine is not None) == spine_kernel.AVAILABLE


@pytest.mark.skipif(not spine_kernel.AVAILABLE, reason="numba not installed")
@pytest.mark.parametrize("weights", FLAVOURS)
def test_kernel_at_the_range_ends_gives_the_inner_derivative(weights: SpineWeights | None) -> None:
    """Exactly at a torso angle's bound (where a bounded IK step puts it) every joint sits at its
    limit and the derivative is the one from inside the range: each column sums to 1 (the sum of the
    joints follows the angle), close to the reference's just inside the bound."""
    driver = SpineDriver(weights)
    lo, hi = driver.group_limits()
    for bound, inward in ((lo, 1e-7), (hi, -1e-7)):
        out, jac = driver.evaluate(bound)
        assert np.allclose(jac.sum(axis=0), 1.0, atol=1e-9)
        _, inner = reference(driver, bound + inward)
        assert np.allclose(jac, inner, atol=1e-4)
