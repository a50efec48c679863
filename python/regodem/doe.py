"""Central composite designs, response-surface fits and their solves on numpy arrays:
`regodem doe ccd` and `regodem fit` (docs/calibration.md) without CSV files between."""
import numpy as np

from . import _regodem

Fit = _regodem.Fit


def ccd(factors, alpha="rotatable", centre_points=3, half_fraction=False, order="standard", seed=1):
    """A central composite design. `factors`: {name: (centre, step)} or {name: (centre,
    step, unit)}, in order; alpha "rotatable", "face" or a number. Returns a dict:
    factors, alpha, coded and actual (runs x factors arrays), point_type, standard_order,
    csv (what `regodem doe ccd` writes)."""
    names, centres, steps, units = [], [], [], []
    for name, spec in factors.items():
        spec = tuple(spec)
        if len(spec) not in (2, 3):
            raise _regodem.InputError(f"ccd: factor '{name}' needs (centre, step) or (centre, step, unit)")
        names.append(str(name))
        centres.append(float(spec[0]))
        steps.append(float(spec[1]))
        units.append(str(spec[2]) if len(spec) == 3 else "")
    if order not in ("standard", "random"):
        raise _regodem.InputError(f"ccd: order must be 'standard' or 'random', got '{order}'")
    return _regodem.ccd(names, centres, steps, units, str(alpha), int(centre_points), bool(half_fraction),
                        order == "random", int(seed))


def fit(x, y, factors, terms=None, response="y"):
    """Fits a response surface by least squares: x (runs x factors, actual units), y
    (runs), `factors` their names, `terms` "A,B,A*B,A^2" (default: the full quadratic).
    Returns a Fit: coefficients, standard_errors, p_values, r_squared, adjusted and
    predicted R², anova, fitted, leverage; equation(), predict(x), solve_for()."""
    x = np.asarray(x, dtype=float)
    if x.ndim == 1:
        x = x.reshape(-1, 1)
    return _regodem.fit(np.ascontiguousarray(x), np.asarray(y, dtype=float).tolist(), list(factors),
                        terms or "", str(response))


def solve(fits, targets, at, free, low, high):
    """Several responses at their targets at once (as many fits as free factors): every
    solution found by Newton's method from a grid over the design range low..high, each
    {factors, outside, inside}; factors not free stay at `at`."""
    return _regodem.solve(list(fits), [float(t) for t in targets], [float(v) for v in at], list(free),
                          [float(v) for v in low], [float(v) for v in high])
