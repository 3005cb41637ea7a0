"""contactbench from Python: the catalogue, and `run` and `compare` as the suite driver runs
them, their records returned as pandas DataFrames (docs/python.md).

Every keyword argument is the command line's option of the same name, with '_' for '-'
(`arc_length=0.05` is `--arc-length 0.05`): True gives a flag, a list or tuple a
comma-separated value, a dict a repeatable option (`set={"n": 10}` is `--set n=10`; compare's
`option={"implicit-fb": {"gamma_tol": 1e-9}}` is `--option implicit-fb:gamma_tol=1e-9`). The
C++ option parser checks them, with the driver's messages. Files are written only with
`out=DIR`, exactly as `contactbench run --out DIR` writes them; otherwise the records stay in
memory. Ctrl-C stops a run as SIGINT stops the driver: the records so far are kept, and
`Interrupted` (a KeyboardInterrupt) carries them.
"""

import io
import json
import os

import pandas as pd

from . import _core

__all__ = ["catalogue", "problems", "parameters", "formulations", "solvers",
           "linear_solvers", "accepts", "run", "compare", "Result", "Interrupted",
           "UsageError", "EXIT_OK", "EXIT_FAILURE", "EXIT_INTERRUPTED"]

UsageError = _core.UsageError
EXIT_OK = _core.EXIT_OK
EXIT_FAILURE = _core.EXIT_FAILURE
EXIT_INTERRUPTED = _core.EXIT_INTERRUPTED

# The record files a run or comparison may write, by attribute of Result.
RECORD_FILES = ("steps", "iterations", "kinks", "critical", "runs", "solution", "contacts",
                "parameters", "problems")


def catalogue():
    """Problems (with their parameters), formulations, solvers and linear solvers."""
    return _core.catalogue()


def problems():
    """One row per problem: name, description."""
    rows = [{"name": p["name"], "description": p["description"]}
            for p in _core.catalogue()["problems"]]
    return pd.DataFrame(rows, columns=["name", "description"])


def parameters():
    """One row per problem parameter: problem, name, default value, doc."""
    rows = [{"problem": p["name"], **e} for p in _core.catalogue()["problems"]
            for e in p["parameters"]]
    return pd.DataFrame(rows, columns=["problem", "name", "value", "doc"])


def formulations():
    """One row per formulation: name, description, available (its dependency was built)."""
    return pd.DataFrame(_core.catalogue()["formulations"],
                        columns=["name", "description", "available"])


def solvers():
    """The nonlinear solvers of `solver=`."""
    return list(_core.catalogue()["solvers"])


def linear_solvers():
    """The sparse direct solvers of `linear_solver=`."""
    return list(_core.catalogue()["linear_solvers"])


def accepts(formulation, **options):
    """Whether `formulation` takes the problem's steps: (True, "") or (False, the reason)."""
    return _core.accepts(_arguments(dict(options, formulation=formulation)))


def _value(value):
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, (list, tuple)):
        return ",".join(_value(v) for v in value)
    return str(value)


def _arguments(options):
    """The command line of `options` (see the module's doc)."""
    args = []
    for key, value in options.items():
        name = "--" + key.replace("_", "-")
        if value is None or value is False:
            continue
        if value is True:
            args.append(name)
        elif isinstance(value, dict):
            for k, v in value.items():
                if isinstance(v, dict):  # compare --option FORMULATION:KEY=VALUE
                    args += [a for kk, vv in v.items()
                             for a in (name, f"{k}:{kk}={_value(vv)}")]
                else:
                    args += [name, f"{k}={_value(v)}"]
        else:
            args += [name, _value(value)]
    return args


class Result:
    """The records of a run or comparison: `status` (the driver's exit status), `reason`,
    `info` (run.json), `files` ({file name: DataFrame}), and one attribute per record file
    (`steps`, `iterations`, `kinks`, `critical`, `runs`, `solution`, `contacts`,
    `parameters`, `problems`; None when the command does not write that file)."""

    def __init__(self, status, tables, info, out=None):
        self.status = status
        self.files = tables
        self.info = info
        self.reason = info.get("reason", "") if info else ""
        self.out = out
        for name in RECORD_FILES:
            setattr(self, name, tables.get(name + ".csv"))

    @property
    def verified(self):
        """Every step the run took was verified (exit status 0)."""
        return self.status == EXIT_OK

    def __repr__(self):
        files = ", ".join(f"{k} ({len(v)} rows)" for k, v in self.files.items())
        return f"<contactbench.Result status={self.status} {files}>"


class Interrupted(KeyboardInterrupt):
    """Ctrl-C (SIGINT) stopped the run; `result` holds the records written before."""

    def __init__(self, result):
        super().__init__(result.reason or "interrupted")
        self.result = result


def _read_table(source):
    # Column types as read from the files: every column of doubles has a '.' or an exponent.
    return pd.read_csv(source, keep_default_na=False, na_values=["nan", "-nan"])


def _result(status, texts, out):
    if out is None:
        tables = {name: _read_table(io.BytesIO(text)) for name, text in texts.items()
                  if name.endswith(".csv")}
        info = json.loads(texts["run.json"]) if "run.json" in texts else {}
    else:
        tables = {name: _read_table(os.path.join(out, name)) for name in sorted(os.listdir(out))
                  if name.endswith(".csv")}
        path = os.path.join(out, "run.json")
        info = json.load(open(path)) if os.path.exists(path) else {}
    result = Result(status, tables, info, out)
    if status == EXIT_INTERRUPTED:
        raise Interrupted(result)
    return result


def _execute(command, options):
    out = options.get("out")
    status, texts = _core.execute(command, _arguments(options))
    return _result(status, texts, None if out is None else os.fspath(out))


def run(problem=None, formulation=None, **options):
    """`contactbench run` with these options; returns a Result. A run that stops on a failure
    returns too (status EXIT_FAILURE, the records up to it); bad options raise UsageError."""
    return _execute("run", dict(options, problem=problem, formulation=formulation))


def compare(problem=None, formulations=None, **options):
    """`contactbench compare` with these options (formulations: a list of names); returns a
    Result whose `runs` has one row per formulation and start."""
    return _execute("compare", dict(options, problem=problem, formulations=formulations))
