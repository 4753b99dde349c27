// Numbers in messages, summaries, the scene reference and expanded scenes, written the way
// std::ostream writes a double by default: six significant digits, the shorter of fixed and
// scientific notation ("0.0125", "1e-05", "2").
#pragma once

#include <iomanip>
#include <sstream>
#include <string>

namespace ddafem
{
inline std::string format_number(const double v)
{
  std::ostringstream s;
  s << v;
  return s.str();
}

/// `v` with `digits` significant digits, shorter than format_number for the derived numbers of
/// `check`, warnings and run logs ("2.5e+10", "0.333"): 4 unless told.
inline std::string format_significant(const double v, const int digits = 4)
{
  std::ostringstream s;
  s << std::setprecision(digits) << v;
  return s.str();
}

/// A time t [s] with its unit: "0.0125 s".
inline std::string format_time(const double t)
{
  return format_number(t) + " s";
}

/// A point (x, y) [m] for messages: "(x, y)".
inline std::string format_point(const double x, const double y)
{
  return "(" + format_number(x) + ", " + format_number(y) + ")";
}
} // namespace ddafem
