#include "io/input_bounds.h"

#include "io/input_error.h"
#include "io/json_node.h"

namespace cb::io {

void CheckJsonDepth(const std::string& text, const std::string& file, int max_depth) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') {
        ++i;  // the escaped character, a quote among them
      } else if (c == '"') {
        in_string = false;
      }
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > max_depth) {
        throw InputError(file, LineColumn(text, i + 1),
                         "arrays and objects nested more than " + std::to_string(max_depth) +
                             " deep; no problem file nests so deep");
      }
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;  // an unbalanced bracket is the parser's to report
    }
  }
}

}  // namespace cb::io
