"""A step as data, the verdict as a function, and a Python formulation run like a built-in one
(docs/your-own-method.md)."""

import os
import subprocess
import sys

import numpy as np
import pytest

import contactbench as cb

ROOT = os.path.join(os.path.dirname(__file__), "..", "..")
EXAMPLE = os.path.join(ROOT, "examples", "python", "compare_my_newton.py")
sys.path.insert(0, os.path.dirname(EXAMPLE))
from compare_my_newton import my_newton  # noqa: E402


@pytest.fixture(scope="module")
def arch_step():
    return cb.step("arch-curved", 3, steps=4)


def test_the_traced_answer_solves_the_step_system_and_is_verified(arch_step):
    s, x = arch_step.system, arch_step.traced
    assert s.rows + len(s.pair_gaps) == s.size  # F and the pairs make a square system
    assert s.size == s.dofs + 2 * s.pairs + 1
    assert np.abs(s.F(x)).max() < 1e-6
    a, b = x[s.pair_gaps], -x[s.pair_reactions]
    assert np.abs(np.minimum(a, b)).max() < 1e-8  # the pairs' complementarity
    verdict = cb.judge(arch_step, x)
    assert verdict["verified"] and verdict["tolerance"] == arch_step.tolerance
    assert np.all(s.lower[s.pair_gaps] == 0) and np.all(s.upper[s.pair_reactions] == 0)


def test_the_jacobian_is_the_derivative_of_F(arch_step):
    s, x = arch_step.system, arch_step.warm_start
    j = s.jacobian(x).toarray()
    assert j.shape == (s.rows, s.size)
    rng = np.random.default_rng(1)
    direction = rng.standard_normal(s.size)
    h = 1e-6
    fd = (s.F(x + h * direction) - s.F(x - h * direction)) / (2 * h)
    assert np.allclose(j @ direction, fd, rtol=1e-5, atol=1e-6 * np.abs(fd).max())


def test_the_warm_start_holds_the_gap_rows_and_the_step_constraint(arch_step):
    s, x = arch_step.system, arch_step.warm_start
    f = s.F(x)
    assert np.abs(f[s.dofs:]).max() < 1e-10  # (30) / L and (33) hold there (docs/method.md 4)
    assert np.all(arch_step.cold_start[s.pair_gaps] == -1.0)  # the report's cold start


def test_the_verdict_refuses_a_moved_point(arch_step):
    x = arch_step.traced.copy()
    x[: arch_step.system.dofs] *= 1.01
    verdict = cb.judge(arch_step, x)
    assert not verdict["verified"] and verdict["eq_res"] > verdict["tolerance"]


def test_a_python_formulation_runs_like_a_built_in_one():
    cb.register("test-fb-newton", my_newton)
    assert "test-fb-newton" in set(cb.formulations()["name"])
    assert cb.accepts("test-fb-newton", problem="arch-flat") == (True, "")
    result = cb.compare(problem="arch-flat", formulations=["test-fb-newton", "active-set"],
                        starts="warm", steps=4)
    assert result.status == cb.EXIT_OK
    mine = result.steps.query("formulation == 'test-fb-newton'")
    assert len(mine) == 4 and mine["verified"].all()
    assert (mine["iterations"] > 0).all() and (mine["residual_evals"] > 0).all()
    assert (mine["time_s"] > 0).all() and set(mine["solver"]) == {"external"}
    iterations = result.iterations.query("formulation == 'test-fb-newton'")
    assert len(iterations) == 0  # the method kept no per-iteration history


def test_a_wrong_point_is_recorded_as_failed_by_the_verdict():
    def wrong(system, x0):  # claims success with the start moved off the solution
        x = x0.copy()
        x[: system.dofs] += 1e-3
        return x, {"iterations": 1, "converged": True}
    cb.register("test-wrong-point", wrong)
    result = cb.run(problem="arch-flat", formulation="test-wrong-point", steps=2, max_cutbacks=1)
    assert result.status == cb.EXIT_FAILURE
    assert len(result.steps) >= 1
    assert result.steps["found"].all() and not result.steps["verified"].any()


def test_a_method_that_raises_is_a_failed_step_with_its_message():
    def raising(system, x0):
        raise RuntimeError("my bug")
    cb.register("test-raising", raising)
    result = cb.run(problem="arch-flat", formulation="test-raising", steps=1, max_cutbacks=0)
    assert result.status == cb.EXIT_FAILURE
    assert "my bug" in result.steps["message"].iloc[0]
    assert not result.steps["found"].any()


def test_a_name_registered_twice_or_a_bad_name_is_refused():
    cb.register("test-twice", my_newton)
    with pytest.raises(ValueError, match="already registered"):
        cb.register("test-twice", my_newton)
    with pytest.raises(ValueError, match="letters, digits"):
        cb.register("bad name", my_newton)
    with pytest.raises(ValueError, match="already registered"):
        cb.register("implicit-fb", my_newton)


def test_the_example_prints_the_table_and_writes_the_profile(tmp_path):
    package = os.path.dirname(os.path.dirname(os.path.abspath(cb.__file__)))
    done = subprocess.run([sys.executable, EXAMPLE, str(tmp_path / "figures"), "--steps", "3"],
                          capture_output=True, text=True, cwd=tmp_path,
                          env=dict(os.environ, PYTHONPATH=package))
    assert done.returncode == 0, done.stderr
    assert "my-newton" in done.stdout and "implicit-fb" in done.stdout
    assert os.path.getsize(tmp_path / "figures" / "profile.png") > 0
    assert sorted(os.listdir(tmp_path)) == ["figures"]  # nothing else written


@pytest.mark.skipif(not os.path.exists(os.environ.get("CONTACTBENCH_PLUGIN", "")),
                    reason="examples/plugin is not built (archives without -fPIC)")
def test_a_cpp_plugin_loads_once_and_compares_like_a_built_in_one():
    cb.load_plugin(os.environ["CONTACTBENCH_PLUGIN"])
    with pytest.raises(cb.UsageError, match="already registered"):
        cb.load_plugin(os.environ["CONTACTBENCH_PLUGIN"])
    result = cb.compare(problem="arch-flat", formulations=["min-newton"], starts="warm", steps=3)
    assert result.status == cb.EXIT_OK and result.steps["verified"].all()
