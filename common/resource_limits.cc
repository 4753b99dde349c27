#include "common/resource_limits.h"

#include "common/format.h"
#include "common/input_error.h"

#include <cmath>
#include <fstream>
#include <sstream>

namespace ddafem
{
ResourceLimits ResourceLimits::of_this_machine()
{
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  double kilobytes = 0.0;
  std::string unit;
  while (meminfo >> key >> kilobytes >> unit)
    if (key == "MemAvailable:")
    {
      const double available = 1024.0 * kilobytes;
      return {0.9 * available,
              "90 % of the " + format_bytes(available) + " available on this machine"};
    }
  return {};
}

ResourceLimits ResourceLimits::given(const std::string& text)
{
  std::istringstream in(text);
  double value = 0.0;
  std::string suffix;
  in >> value;
  const bool number_read = !in.fail();
  std::getline(in, suffix);
  double scale = 0.0;
  if (suffix.empty())
    scale = 1.0;
  else if (suffix == "K" || suffix == "k")
    scale = 1e3;
  else if (suffix == "M")
    scale = 1e6;
  else if (suffix == "G")
    scale = 1e9;
  else if (suffix == "T")
    scale = 1e12;
  if (!number_read || !(value > 0.0) || !std::isfinite(value) || scale == 0.0)
    throw InputError("command line --max-memory = '" + text +
                     "': expected a positive size in bytes, with K, M, G or T (e.g. 8G)");
  return {value * scale, "the --max-memory " + text};
}

std::string ResourceLimits::too_much(double bytes) const
{
  return "about " + format_bytes(bytes) + " of memory, more than " + source +
         (source.rfind("the --max-memory", 0) == 0 ? "" : " (--max-memory sets another limit)");
}

double estimate_far_field_dofs(const double area, const double h, const double hole_perimeter,
                               const double h0, const double growth_ratio, const unsigned degree)
{
  const double far_cells = area / (h * h);
  // The quadtree refinement towards the hole ends each cell between half and the whole of its
  // allowed size, and keeps neighbours within one level: the examples' rings hold 2 to 6 times
  // the cells of the integral (circular_hole: 5.6).
  constexpr double refinement = 6.0;
  const double ring_cells =
      h0 > 0.0 && h0 < h && growth_ratio > 1.0
          ? refinement * hole_perimeter / (growth_ratio - 1.0) * (1.0 / h0 - 1.0 / h)
          : 0.0;
  return 2.0 * degree * degree * (far_cells + ring_cells);
}

std::string format_bytes(double bytes)
{
  if (bytes >= 1e9)
    return format_significant(bytes / 1e9, 3) + " GB";
  return format_significant(bytes / 1e6, 3) + " MB";
}

} // namespace ddafem
