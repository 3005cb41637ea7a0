#include "core/types.h"

namespace cb {

const char* ToString(Status status) {
  switch (status) {
    case Status::kNotRun:
      return "not_run";
    case Status::kConverged:
      return "converged";
    case Status::kLimitReached:
      return "limit_reached";
    case Status::kTimeLimit:
      return "time_limit";
    case Status::kFailed:
      return "failed";
    case Status::kStoppedByCaller:
      return "stopped_by_caller";
  }
  return "unknown";
}

}  // namespace cb
