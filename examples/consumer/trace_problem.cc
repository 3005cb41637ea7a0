// Loads a problem file and traces it with implicit-fb and the suite's defaults for the problem
// (what `contactbench run --problem-file F --formulation implicit-fb` does, without records),
// then prints one line per accepted step and the summary. Exit status 0 when every step was
// verified.
#include <contactbench/formulations/registry.h>
#include <contactbench/io/problem_file.h>
#include <contactbench/path/path.h>
#include <contactbench/problems/problem_path.h>

#include <cstdio>
#include <exception>

namespace {

// Prints the accepted steps as they come.
class StepPrinter final : public cb::PathObserver {
 public:
  void OnAttempt(const cb::StepAttempt& attempt) override {
    if (!attempt.accepted) return;
    std::printf("step %d: lambda %.6g, %d iterations, %d pairs in contact\n", attempt.step,
                attempt.state.lambda, attempt.result.counts.iterations, attempt.n_contact);
  }
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: trace_problem PROBLEM_FILE.json\n");
    return 2;
  }
  try {
    const cb::Problem problem = cb::io::LoadProblemFile(argv[1]);
    auto formulation = cb::MakeFormulation("implicit-fb", cb::FormulationConfig());
    const cb::PathOptions options = cb::DefaultPathOptions(problem);
    StepPrinter printer;
    const cb::PathSummary summary = cb::TraceProblem(problem, *formulation, options, &printer);
    std::printf("%s: %s (%d accepted steps, %d kinks)\n", problem.name.c_str(),
                summary.message.c_str(), summary.accepted_steps, summary.kinks);
    return summary.status == cb::Status::kConverged ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "trace_problem: %s\n", e.what());
    return 2;
  }
}
