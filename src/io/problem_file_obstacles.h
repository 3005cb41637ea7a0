// The "obstacles" of a body problem file (half-spaces, balls, cylinders in 3-D), each with its
// id. Internal to the problem-file reader.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "io/json_node.h"
#include "model/obstacle.h"

namespace cb::io::reading {

struct Obstacles {
  std::vector<std::shared_ptr<const Obstacle>> list;
  std::vector<std::string> ids;

  // The index of the obstacle an id names; an unknown id is refused with the ids defined.
  int Find(const JsonNode& ref) const;
};

Obstacles ReadObstacles(const JsonNode& root, int dim);

}  // namespace cb::io::reading
