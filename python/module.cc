// The extension behind the Python package `contactbench` (python/contactbench/__init__.py,
// docs/python.md): the catalogue, and `run` and `compare` through the same functions the suite
// driver calls (harness/commands.h), with the same option parser. Nothing of the method is
// here: the package turns keyword arguments into the command line's options and the record
// texts into pandas DataFrames.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <map>
#include <string>
#include <vector>

#include "core/csv.h"
#include "formulations/registry.h"
#include "harness/cli.h"
#include "harness/commands.h"
#include "harness/interrupt.h"
#include "harness/options.h"
#include "harness/records_doc.h"
#include "problems/problem.h"
#include "solvers/equation_solver.h"
#include "solvers/linear_solver.h"
#include "step_bindings.h"

namespace py = pybind11;

namespace cb::harness {
namespace {

py::dict Catalogue() {
  py::list problems;
  for (const auto& info : ProblemRegistry()) {
    py::list parameters;
    const Parameters defaults = info.defaults();
    for (const auto& e : defaults.entries()) {
      parameters.append(
          py::dict(py::arg("name") = e.name, py::arg("value") = e.value, py::arg("doc") = e.doc));
    }
    problems.append(py::dict(py::arg("name") = info.name, py::arg("description") = info.description,
                             py::arg("parameters") = parameters));
  }
  py::list formulations;
  for (const auto& info : FormulationRegistry()) {
    formulations.append(py::dict(py::arg("name") = info.name,
                                 py::arg("description") = info.description,
                                 py::arg("available") = info.available));
  }
  py::dict catalogue;
  catalogue["problems"] = problems;
  catalogue["formulations"] = formulations;
  catalogue["solvers"] = EquationSolverNames();
  catalogue["linear_solvers"] = LinearSolverNames();
  return catalogue;
}

Command PathCommand(const std::string& name) {
  const CommandInfo* info = FindCommand(name);
  if (info == nullptr || (info->command != kRun && info->command != kCompare)) {
    throw std::logic_error("contactbench._core: not a path command: " + name);
  }
  return info->command;
}

// Whether `run` with these options would take the problem: (accepted, reason).
py::tuple Accepts(const std::vector<std::string>& args) {
  const RunArguments a = ParseArguments(kRun, args, /*out_optional=*/true);
  std::string reason;
  bool accepted = false;
  {
    py::gil_scoped_release release;
    accepted = AcceptsProblem(a, &reason);
  }
  return py::make_tuple(accepted, reason);
}

// `contactbench run|compare ARGS`: (exit status, {file name: text}); the texts are empty when
// the records went to --out. Ctrl-C stops the run as SIGINT stops the driver.
py::tuple Execute(const std::string& command, const std::vector<std::string>& args) {
  const Command which = PathCommand(command);
  const RunArguments a = ParseArguments(which, args, /*out_optional=*/true);
  RunJson record;
  record.command_line = {"contactbench (python)", command};
  record.command_line.insert(record.command_line.end(), args.begin(), args.end());
  record.command = command;
  RecordTexts memory;
  RecordTexts* texts = a.out.empty() ? &memory : nullptr;
  int status = kExitFailure;
  {
    py::gil_scoped_release release;
    const InterruptScope interrupts;
    status = which == kRun ? RunCommand(a, &record, texts) : CompareCommand(a, &record, texts);
  }
  py::dict files;
  for (const auto& [name, text] : memory) files[py::str(name)] = py::bytes(text);
  return py::make_tuple(status, files);
}

}  // namespace
}  // namespace cb::harness

PYBIND11_MODULE(_core, m) {
  using namespace cb::harness;
  m.doc() = "contactbench's C++ core (the package `contactbench` wraps it; docs/python.md)";
  static py::exception<UsageError> usage_error(m, "UsageError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const UsageError& e) {  // InputError too
      usage_error(e.what());
    } catch (const Interrupted& e) {
      PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
    } catch (const cb::WriteError& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    }
  });
  m.def("catalogue", &Catalogue, "problems, formulations, solvers and linear solvers");
  m.def("accepts", &Accepts, py::arg("args"));
  m.def("execute", &Execute, py::arg("command"), py::arg("args"));
  BindSteps(m);
  m.def("records_markdown", &RecordsMarkdown, "the record files' columns (docs/records.md)");
  m.attr("EXIT_OK") = kExitOk;
  m.attr("EXIT_BAD_ARGUMENTS") = kExitBadArguments;
  m.attr("EXIT_FAILURE") = kExitFailure;
  m.attr("EXIT_INTERRUPTED") = kExitInterrupted;
}
