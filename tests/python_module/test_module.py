"""The Python module `contactbench` (docs/python.md), run by ctest with PYTHONPATH=build/python
and CONTACTBENCH_BINARY naming this build's driver."""

import os
import signal
import subprocess
import threading
import time

import pandas as pd
import pytest

import contactbench as cb

BINARY = os.environ.get("CONTACTBENCH_BINARY", "contactbench")

# Short paths, so that every test runs in seconds.
ARCH = dict(problem="arch-flat", steps=6)


def cli(tmp_path, *args):
    out = tmp_path / "cli"
    done = subprocess.run([BINARY, *args, "--out", str(out)], capture_output=True, text=True)
    return done.returncode, out


def without_time(frame):
    """The records less the solve's wall times (the median and its range), which differ between
    two runs."""
    times = ("time_s", "time_min_s", "time_max_s")
    return frame.drop(columns=[c for c in times if c in frame.columns])


def test_catalogue_lists_problems_parameters_formulations_and_solvers():
    names = list(cb.problems()["name"])
    assert "block" in names and "arch-flat" in names
    block = cb.parameters().query("problem == 'block'")
    assert "n" in set(block["name"])
    formulations = cb.formulations().set_index("name")
    assert formulations.loc["implicit-fb", "available"]
    assert formulations["description"].str.len().min() > 0
    assert "newton" in cb.solvers()
    assert len(cb.linear_solvers()) >= 1


def test_accepts_gives_the_formulation_s_reason():
    ok, reason = cb.accepts("implicit-fb", problem="block", set={"n": 4})
    assert ok and reason == ""
    refusals = [(f, cb.accepts(f, problem="block", set={"n": 4}))
                for f in cb.formulations().query("available")["name"]]
    for name, (accepted, why) in refusals:
        assert accepted or why, name  # a refusal always says why


def test_run_in_memory_equals_the_cli_records_and_writes_nothing(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    result = cb.run(formulation="implicit-fb", **ARCH)
    assert os.listdir(tmp_path) == []  # no file without out=
    status, out = cli(tmp_path, "run", "--problem", "arch-flat", "--formulation",
                      "implicit-fb", "--steps", "6")
    assert result.status == status == cb.EXIT_OK
    assert result.verified
    for name in ("steps.csv", "iterations.csv", "kinks.csv", "critical.csv", "parameters.csv",
                 "solution.csv", "contacts.csv"):
        from_cli = cb._read_table(str(out / name))
        assert list(result.files[name].columns) == list(from_cli.columns), name
        pd.testing.assert_frame_equal(without_time(result.files[name]), without_time(from_cli))
    assert len(result.steps) >= 6 and result.steps["verified"].all()
    assert result.info["exit_status"] == cb.EXIT_OK


def test_run_with_out_writes_the_cli_s_files(tmp_path):
    result = cb.run(formulation="implicit-fb", out=tmp_path / "records", **ARCH)
    written = sorted(os.listdir(tmp_path / "records"))
    assert "run.json" in written and "steps.csv" in written
    assert result.out == str(tmp_path / "records")
    assert result.info["reason"] == result.reason != ""
    memory = cb.run(formulation="implicit-fb", **ARCH)
    pd.testing.assert_frame_equal(without_time(result.steps), without_time(memory.steps))


def test_compare_returns_one_outcome_per_formulation_and_start(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    result = cb.compare(formulations=["implicit-fb", "active-set"], starts=["warm", "cold"],
                        **ARCH)
    assert os.listdir(tmp_path) == []
    assert len(result.runs) == 4
    assert set(result.runs["formulation"]) == {"implicit-fb", "active-set"}
    assert set(result.steps["mode"]) == {"replay"}
    status, out = cli(tmp_path, "compare", "--problem", "arch-flat", "--formulations",
                      "implicit-fb,active-set", "--starts", "warm,cold", "--steps", "6")
    assert status == result.status
    from_cli = cb._read_table(str(out / "runs.csv"))
    pd.testing.assert_frame_equal(result.runs, from_cli)


def test_a_problem_set_returns_one_row_per_problem_formulation_and_start(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    data = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "fclib")
    files = ",".join(os.path.join(data, f) for f in ("CubeH8.hdf5", "Capsules-i125-1213.hdf5"))
    result = cb.compare(problem_dir=files, set={"friction": "ignore"},
                        formulations=["active-set", "siconos-lemke"])
    assert os.listdir(tmp_path) == []
    assert result.runs is None
    # CubeH8 cold; Capsules cold and from its one guess.
    assert len(result.problems) == 6
    assert set(result.problems["start"]) == {"cold", "guess:1"}
    status, out = cli(tmp_path, "compare", "--problem-dir", files, "--set", "friction=ignore",
                      "--formulations", "active-set,siconos-lemke")
    assert status == result.status
    from_cli = cb._read_table(str(out / "problems.csv"))
    pd.testing.assert_frame_equal(without_time(result.problems), without_time(from_cli))


def test_bad_options_are_refused_with_the_option_named():
    with pytest.raises(cb.UsageError, match="--steps"):
        cb.run(formulation="implicit-fb", problem="arch-flat", steps=-1)
    with pytest.raises(cb.UsageError, match="unknown option '--stepz'.*--steps"):
        cb.run(formulation="implicit-fb", problem="arch-flat", stepz=3)
    with pytest.raises(cb.UsageError, match="gama_tol"):
        cb.run(formulation="implicit-fb", problem="arch-flat", option={"gama_tol": 1e-9})
    with pytest.raises(cb.UsageError, match="--save-every"):
        cb.run(formulation="implicit-fb", problem="block", save_every=1)


def test_sigint_stops_a_run_and_keeps_its_records():
    # A path long enough to be running when the signal comes (seconds), stopped well before.
    timer = threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    with pytest.raises(cb.Interrupted) as stopped:
        cb.run(formulation="implicit-fb", problem="arch-flat", steps=100000,
               arc_length=1e-4)
    timer.join()
    result = stopped.value.result
    assert isinstance(stopped.value, KeyboardInterrupt)
    assert result.status == cb.EXIT_INTERRUPTED
    assert 0 < len(result.steps) < 100000
    assert "stopped by the caller" in result.reason  # as the driver says it
    # Python's own handler is back: the next SIGINT raises KeyboardInterrupt as usual.
    with pytest.raises(KeyboardInterrupt):
        os.kill(os.getpid(), signal.SIGINT)
        time.sleep(5)
