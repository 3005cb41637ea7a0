// The step as data and formulations registered from Python (docs/your-own-method.md): the
// bindings of formulations/external/ (the step system, the formulation around a callable) and
// of the verdict. The package (python/contactbench/method.py) turns them into numpy, scipy and
// a registration function; nothing of the method is computed here.
#include "step_bindings.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "formulations/external/callback_formulation.h"
#include "formulations/registry.h"
#include "harness/options.h"
#include "harness/path_step.h"
#include "harness/plugins.h"
#include "verdict/verdict.h"

namespace py = pybind11;

namespace cb::harness {
namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

Vec ToVec(const Array& x) {
  Vec v(x.size());
  for (py::ssize_t i = 0; i < x.size(); ++i) v[i] = x.data()[i];
  return v;
}

py::array_t<double> ToArray(const Vec& v) {
  py::array_t<double> a(v.size());
  for (Eigen::Index i = 0; i < v.size(); ++i) a.mutable_data()[i] = v[i];
  return a;
}

Vec Sized(const ExternalStepSystem& s, const Array& x) {
  if (x.ndim() != 1 || x.size() != s.size()) {
    throw std::invalid_argument("x: " + std::to_string(s.size()) + " unknowns expected, not " +
                                std::to_string(x.size()));
  }
  return ToVec(x);
}

// F's Jacobian as the pieces of a scipy.sparse.csc_matrix: (data, indices, indptr, shape).
py::tuple CscPieces(const SpMat& j) {
  const auto nnz = static_cast<py::ssize_t>(j.nonZeros());
  py::array_t<double> data(nnz);
  py::array_t<int> indices(nnz);
  py::array_t<int> indptr(j.outerSize() + 1);
  std::copy(j.valuePtr(), j.valuePtr() + nnz, data.mutable_data());
  std::copy(j.innerIndexPtr(), j.innerIndexPtr() + nnz, indices.mutable_data());
  std::copy(j.outerIndexPtr(), j.outerIndexPtr() + j.outerSize() + 1, indptr.mutable_data());
  return py::make_tuple(data, indices, indptr, py::make_tuple(j.rows(), j.cols()));
}

py::dict VerdictDict(const Verdict& v) {
  return py::dict(py::arg("eq_res") = v.eq_res, py::arg("comp_res") = v.comp_res,
                  py::arg("feas_res") = v.feas_res, py::arg("step_res") = v.step_res,
                  py::arg("verified") = v.verified, py::arg("tolerance") = v.tolerance);
}

void BindStepSystem(py::module_& m) {
  py::class_<ExternalStepSystem>(m, "StepSystem")
      .def_property_readonly("size", &ExternalStepSystem::size)
      .def_property_readonly("rows", &ExternalStepSystem::rows)
      .def_property_readonly("dofs", [](const ExternalStepSystem& s) { return s.layout().d; })
      .def_property_readonly("pairs", [](const ExternalStepSystem& s) { return s.layout().nc; })
      .def_property_readonly("length_scale",
                             [](const ExternalStepSystem& s) { return s.step().scales.length; })
      .def_property_readonly("force_scale",
                             [](const ExternalStepSystem& s) { return s.step().scales.force; })
      .def_property_readonly("constraint",
                             [](const ExternalStepSystem& s) {
                               return std::string(ToString(s.step().constraint.kind));
                             })
      .def_property_readonly("pair_gaps", &ExternalStepSystem::pair_gaps)
      .def_property_readonly("pair_reactions", &ExternalStepSystem::pair_reactions)
      .def_property_readonly("lower",
                             [](const ExternalStepSystem& s) { return ToArray(s.lower()); })
      .def_property_readonly("upper",
                             [](const ExternalStepSystem& s) { return ToArray(s.upper()); })
      .def(
          "residual",
          [](ExternalStepSystem& s, const Array& x) {
            Vec f;
            s.Residual(Sized(s, x), &f);
            return ToArray(f);
          },
          py::arg("x"))
      .def(
          "jacobian_pieces",
          [](ExternalStepSystem& s, const Array& x) { return CscPieces(s.Jacobian(Sized(s, x))); },
          py::arg("x"))
      .def(
          "judge",
          [](const ExternalStepSystem& s, const Array& x, double tolerance) {
            return VerdictDict(Judge(s.step(), s.ToPoint(Sized(s, x)), tolerance));
          },
          py::arg("x"), py::arg("tolerance"));
}

void BindPathStep(py::module_& m) {
  py::class_<PathStep>(m, "PathStep")
      .def_property_readonly("problem", [](const PathStep& p) { return p.problem.name; })
      .def_property_readonly("index", [](const PathStep& p) { return p.index; })
      .def_property_readonly("tolerance", [](const PathStep& p) { return p.tolerance; })
      .def_property_readonly(
          "system", [](const PathStep& p) { return p.system.get(); },
          py::return_value_policy::reference_internal)
      .def_property_readonly("warm_start",
                             [](const PathStep& p) { return ToArray(p.system->Start(p.warm)); })
      .def_property_readonly("cold_start",
                             [](const PathStep& p) { return ToArray(p.system->Start(p.cold)); })
      .def_property_readonly(
          "traced", [](const PathStep& p) { return ToArray(p.system->FromPoint(p.traced)); });
  m.def(
      "step",
      [](const std::vector<std::string>& args, int k) {
        const RunArguments a = ParseArguments(kRun, args, /*out_optional=*/true);
        py::gil_scoped_release release;
        return StepOfPath(a, k);
      },
      py::arg("args"), py::arg("k"));
}

// The Python method's answer (x, converged, message, counts) as the formulation's.
ExternalAnswer ToAnswer(const py::tuple& out) {
  ExternalAnswer answer;
  answer.x = ToVec(out[0].cast<Array>());
  answer.status = out[1].cast<bool>() ? Status::kConverged : Status::kFailed;
  answer.message = out[2].cast<std::string>();
  const auto counts = out[3].cast<std::map<std::string, int>>();
  auto count = [&](const char* key) {
    const auto it = counts.find(key);
    return it == counts.end() ? 0 : it->second;
  };
  answer.counts = {count("iterations"), count("residual_evals"), count("jacobian_evals"),
                   count("linear_solves")};
  return answer;
}

// `adapter(system, x0, start, options)` (the package's, around the user's callable) as an
// ExternalMethod: called with the GIL held; a Python exception becomes the method's failure.
ExternalMethod PythonMethod(const py::object& adapter) {
  // Never released: the registry lives until the process ends, after the interpreter.
  auto* held = new py::object(adapter);
  return [held](ExternalStepSystem& system, const ExternalCall& call) {
    py::gil_scoped_acquire gil;
    try {
      const py::object out =
          (*held)(py::cast(&system, py::return_value_policy::reference), ToArray(call.x0),
                  std::string(ToString(call.start)), *call.options);
      return ToAnswer(out.cast<py::tuple>());
    } catch (py::error_already_set& e) {
      throw std::runtime_error(e.what());
    } catch (const py::cast_error& e) {
      throw std::runtime_error(std::string("its answer is not (x, converged, message, counts): ") +
                               e.what());
    }
  };
}

}  // namespace

void BindSteps(py::module_& m) {
  BindStepSystem(m);
  BindPathStep(m);
  m.def(
      "register_formulation",
      [](const std::string& name, const std::string& description, const std::string& solver,
         const py::object& adapter) {
        RegisterFormulation(
            ExternalFormulationInfo(name, description, solver, PythonMethod(adapter)));
      },
      py::arg("name"), py::arg("description"), py::arg("solver"), py::arg("adapter"));
  m.def("load_plugin", &LoadPlugin, py::arg("path"), "a C++ plug-in's formulations (--plugin)");
}

}  // namespace cb::harness
