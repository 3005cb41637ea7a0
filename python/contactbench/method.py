"""Your own method beside the built-in ones (docs/your-own-method.md): a step of a problem's
path as data (`step`), the verdict as a function (`judge`), and a Python callable registered as
a formulation (`register`) that `run` and `compare` then run like a built-in one.

The step system, in the scaled unknowns x = (du, g^, r^, dlambda) (g^ = g / L, r^ = r / R):
F(x) = 0 are the rows (29) / R, (30) / L and the step constraint, and each complementarity pair
i asks 0 <= x[pair_gaps[i]] and 0 <= -x[pair_reactions[i]] with their product zero. F and the
pairs together make a square system.
"""

import numpy as np
import scipy.sparse as sp

from . import _core

__all__ = ["StepSystem", "Step", "step", "judge", "register", "load_plugin"]


class StepSystem:
    """One step's equations and pairs (the module's doc). `F(x)`, `jacobian(x)` (a
    scipy.sparse.csc_matrix, rows x size), `pair_gaps`, `pair_reactions` (index arrays),
    `lower`, `upper` (bounds of x), `length_scale`, `force_scale`, `dofs`, `pairs`, `size`,
    `rows`, `constraint` (the step constraint's kind). Counts its evaluations of F and of the
    Jacobian (`residual_evals`, `jacobian_evals`). Handed to a registered method, it is valid
    during that call only."""

    def __init__(self, core):
        self._core = core
        self.residual_evals = 0
        self.jacobian_evals = 0
        for name in ("size", "rows", "dofs", "pairs", "length_scale", "force_scale",
                     "constraint", "lower", "upper"):
            setattr(self, name, getattr(core, name))
        self.pair_gaps = np.asarray(core.pair_gaps, dtype=int)
        self.pair_reactions = np.asarray(core.pair_reactions, dtype=int)

    def F(self, x):
        """The rows (29) / R, (30) / L [, a kink pair's row] and the step constraint at x."""
        self.residual_evals += 1
        return self._core.residual(np.asarray(x, dtype=float))

    def jacobian(self, x):
        """dF/dx at x, a scipy.sparse.csc_matrix of shape (rows, size)."""
        self.jacobian_evals += 1
        data, indices, indptr, shape = self._core.jacobian_pieces(np.asarray(x, dtype=float))
        return sp.csc_matrix((data, indices, indptr), shape=shape)

    def judge(self, x, tolerance):
        """The verdict on x (see `judge`)."""
        return self._core.judge(np.asarray(x, dtype=float), tolerance)


class Step:
    """Step `index` of a problem's path: `system` (a StepSystem), `warm_start` and `cold_start`
    (the suite's starts of docs/method.md section 4, in the unknowns x), `traced` (the traced
    path's own answer), `tolerance` (the verdict's), `problem`."""

    def __init__(self, core):
        self._core = core  # keeps the model and the system alive
        self.problem = core.problem
        self.index = core.index
        self.tolerance = core.tolerance
        self.system = StepSystem(core.system)
        self.warm_start = core.warm_start
        self.cold_start = core.cold_start
        self.traced = core.traced


def step(problem=None, index=1, formulation="implicit-fb", **options):
    """Step `index` (1-based) of the path `run(problem, formulation, **options)` traces, as a
    comparison's replay gives it to every formulation."""
    from . import _arguments
    args = _arguments(dict(options, problem=problem, formulation=formulation))
    return Step(_core.step(args, int(index)))


def judge(step, x, tolerance=None):
    """The verdict on x as an answer to `step` (a Step), from the model alone: eq_res, comp_res,
    feas_res, step_res, verified (all four <= tolerance; the step's by default), tolerance."""
    tol = step.tolerance if tolerance is None else tolerance
    return step.system.judge(x, tol)


def _answer(out, system):
    """(x, converged, message, counts) from what a method returned: x, or (x, counts) with
    counts a dict of iterations, linear_solves (and optionally converged, message,
    residual_evals, jacobian_evals)."""
    counts = {}
    if isinstance(out, tuple):
        out, counts = out
    counts = dict(counts)
    converged = bool(counts.pop("converged", True))
    message = str(counts.pop("message", ""))
    counts.setdefault("residual_evals", system.residual_evals)
    counts.setdefault("jacobian_evals", system.jacobian_evals)
    counts = {k: int(v) for k, v in counts.items()}
    return np.asarray(out, dtype=float).ravel(), converged, message, counts


def register(name, method, description="", solver="", takes_start=False):
    """Registers `method(system, x0)` as formulation `name`: from then on `run`, `compare`,
    `formulations()` and `accepts` know it as they know a built-in one. `system` is a
    StepSystem, x0 the suite's start (warm or cold as the run asks); the method returns x or
    (x, counts) (see `_answer`). With takes_start=True it is called as
    method(system, x0, start, options), start "warm" or "cold" and options the dict of its
    compare --option values. Its point is judged by the verdict, whatever it claims."""
    def adapter(core, x0, start, options):
        system = StepSystem(core)
        out = method(system, x0, start, options) if takes_start else method(system, x0)
        return _answer(out, system)
    _core.register_formulation(name, description or f"Python: {name}", solver, adapter)


def load_plugin(path):
    """Registers a C++ plug-in's formulations, as `--plugin FILE` does; UsageError (exit 2 on the
    command line) when it cannot be loaded, has no entry point or registers a taken name."""
    _core.load_plugin(str(path))
