// A problem's name becomes file names (vtk/NAME.pvd, vtk/NAME_0000.vtu): the rule every problem
// file reader applies to it.
#pragma once

#include <string>

namespace cb::io {

// Only characters that keep it one name inside the output directory and need no quoting in a
// path or in XML: letters, digits and ._+-, not first '.' or '-'.
bool IsFileSafeName(const std::string& name);

}  // namespace cb::io
