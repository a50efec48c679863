"""Designs, fits and solves on numpy arrays, against what they must give exactly."""
import math

import numpy as np
import pytest

import regodem


def test_a_rotatable_two_factor_design():
    design = regodem.ccd({"A": (10.0, 2.0, "mm"), "B": (0.5, 0.1)}, centre_points=3)
    # 2^2 factorial + 4 axial + 3 centre points; alpha = n_F^(1/4) = sqrt(2).
    assert design["coded"].shape == (11, 2)
    assert design["alpha"] == pytest.approx(math.sqrt(2.0), rel=1e-15)
    assert design["point_type"].count("axial") == 4 and design["point_type"].count("centre") == 3
    assert np.allclose(design["actual"], np.array([10.0, 0.5]) + design["coded"] * np.array([2.0, 0.1]))
    assert design["csv"].splitlines()[0].startswith("run,std_order,point_type")


def test_a_quadratic_is_fitted_exactly_and_solved_in_closed_form():
    design = regodem.ccd({"A": (0.0, 1.0), "B": (0.0, 1.0)}, centre_points=2)
    x = design["actual"]
    # y = 3 + 2A - B + 0.5AB + A^2: the full quadratic recovers it to round-off (1e-9).
    y = 3 + 2 * x[:, 0] - x[:, 1] + 0.5 * x[:, 0] * x[:, 1] + x[:, 0] ** 2
    fit = regodem.fit(x, y, ["A", "B"], response="y")
    coefficients = dict(zip(fit.terms, fit.coefficients))
    expected = {"1": 3.0, "A": 2.0, "B": -1.0, "A*B": 0.5, "A^2": 1.0, "B^2": 0.0}
    for term, value in expected.items():
        assert coefficients[term] == pytest.approx(value, abs=1e-9), term
    assert fit.r_squared == pytest.approx(1.0, abs=1e-12)
    assert np.allclose(fit.predict([[1.0, 1.0]]), [3 + 2 - 1 + 0.5 + 1], atol=1e-9)
    # At B = 0: A^2 + 2A + 3 = 6 has the roots -1 ± 2.
    roots = fit.solve_for(6.0, "A", [0.0, 0.0])
    assert roots == pytest.approx([-3.0, 1.0], abs=1e-9)


def test_two_responses_solved_together():
    design = regodem.ccd({"A": (0.0, 1.0), "B": (0.0, 1.0)}, alpha="face", centre_points=1)
    x = design["actual"]
    f = regodem.fit(x, x[:, 0] + x[:, 1], ["A", "B"], terms="A,B", response="sum")
    g = regodem.fit(x, x[:, 0] - x[:, 1], ["A", "B"], terms="A,B", response="difference")
    # A + B = 1 and A - B = 0.2: A = 0.6, B = 0.4.
    solutions = regodem.solve([f, g], [1.0, 0.2], at=[0.0, 0.0], free=["A", "B"], low=[-1, -1], high=[1, 1])
    assert len(solutions) == 1 and solutions[0]["inside"]
    assert solutions[0]["factors"] == pytest.approx([0.6, 0.4], abs=1e-9)


def test_bad_designs_and_fits_are_input_errors():
    with pytest.raises(regodem.InputError):
        regodem.ccd({"A": (0.0, 1.0)}, alpha="sideways")
    with pytest.raises(regodem.InputError):
        regodem.fit([[0.0], [1.0]], [1.0, 2.0], ["A"])  # fewer runs than the quadratic's terms
