// A number in a message ("t_s 0.1 differs from 0 on line 2"): up to 9 significant digits, no trailing zeros.
#pragma once

#include <sstream>
#include <string>

namespace rk::io {

inline std::string NumberText(double v) {
  std::ostringstream s;
  s.precision(9);
  s << v;
  return s.str();
}

}  // namespace rk::io
