#include "app/schema/bound_keys.h"

#include <cmath>
#include <iomanip>
#include <ios>
#include <sstream>

namespace ddafem::schema
{
namespace
{
/// `v` in `format` with the fewest digits that read back as `v`.
std::string round_trip_text(const double v, std::ios_base::fmtflags format)
{
  std::string text;
  for (int digits = 0; digits <= 17; ++digits)
  {
    std::ostringstream s;
    s.setf(format, std::ios_base::floatfield);
    s << std::setprecision(digits) << v;
    text = s.str();
    if (std::stod(text) == v)
      break;
  }
  return text;
}

/// "1.000000e-06" -> "1e-6", "2.5e+10" -> "2.5e10": the exponent as a person writes it.
std::string plain_exponent(const std::string& text)
{
  const std::size_t e = text.find('e');
  std::string mantissa = text.substr(0, e), exponent = text.substr(e + 1);
  const bool negative = exponent.front() == '-';
  if (exponent.front() == '-' || exponent.front() == '+')
    exponent.erase(0, 1);
  exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
  return mantissa + "e" + (negative ? "-" : "") + exponent;
}

/// `v` >= 1e6 in engineering notation, as rock engineers write moduli: "200e9", "30e9".
std::string engineering_text(const double v)
{
  const int exponent = 3 * static_cast<int>(std::floor(std::log10(std::abs(v)) / 3.0));
  const double mantissa = v / std::pow(10.0, exponent);
  for (int digits = 0; digits <= 17; ++digits)
  {
    std::ostringstream s;
    s << std::fixed << std::setprecision(digits) << mantissa << "e" << exponent;
    if (std::stod(s.str()) == v)
      return s.str();
  }
  return plain_exponent(round_trip_text(v, std::ios_base::scientific));
}
} // namespace

std::string shortest_number_text(const double v)
{
  if (v == std::trunc(v) && std::abs(v) < 1e6)
    return std::to_string(static_cast<long long>(v));
  if (std::abs(v) >= 1e6)
    return engineering_text(v);
  const std::string fixed = round_trip_text(v, std::ios_base::fixed);
  const std::string scientific = plain_exponent(round_trip_text(v, std::ios_base::scientific));
  return scientific.size() < fixed.size() ? scientific : fixed;
}

} // namespace ddafem::schema
