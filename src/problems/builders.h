// Builders of the named problems (docs/problems.md). Each has a Defaults() declaring its parameters
// and a Build() from them; the registry wires them to names.
#pragma once

#include <string>

#include "problems/problem.h"

namespace cb {

// A problem traced by arc length: the step theta and the number of steps from the parameters
// "arc_length" and "steps", and the displacement recorded as control_disp.
void TraceByArcLength(const Parameters& parameters, int control_dof, std::string control_label,
                      Problem* problem);

Parameters BlockDefaults();
Problem BuildBlock(const Parameters& p);

Parameters ArchFlatDefaults();
Parameters ArchCurvedDefaults();
Problem BuildArch(const Parameters& p);

Parameters BarWallDefaults();
Problem BuildBarWall(const Parameters& p);

Parameters TwoBarDefaults();
Parameters TwoBarObstacleDefaults();
Problem BuildTwoBar(const Parameters& p);

Parameters HertzDefaults();
Problem BuildHertz(const Parameters& p);

Parameters PlateDefaults();
Problem BuildPlate(const Parameters& p);

}  // namespace cb
