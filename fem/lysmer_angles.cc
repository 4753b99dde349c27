// Prints measured and analytic Lysmer reflection coefficients as JSON (tools/verify_lysmer.py).
// Usage: lysmer_angles [elements_per_wavelength [domain_factor [P|SV angle_deg]]]
#include "fem/lysmer_measurement.h"

#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

namespace
{
std::string number(const std::optional<double>& x)
{
  if (!x)
    return "null";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6f", *x);
  return buffer;
}
} // namespace

int main(int argc, char** argv)
{
  using namespace ddafem::fem;
  LysmerMeasurementSettings base;
  if (argc > 1)
    base.elements_per_wavelength = std::atof(argv[1]);
  if (argc > 2)
    base.domain_factor = std::atof(argv[2]);
  std::vector<std::pair<IncidentKind, double>> cases;
  if (argc > 4)
    cases.emplace_back(std::string(argv[3]) == "P" ? IncidentKind::p : IncidentKind::sv,
                       std::atof(argv[4]));
  else
    for (const auto kind : {IncidentKind::p, IncidentKind::sv})
      for (const double angle : {0.0, 15.0, 30.0, 45.0, 60.0})
        cases.emplace_back(kind, angle);
  std::printf("[\n");
  for (std::size_t i = 0; i < cases.size(); ++i)
  {
    LysmerMeasurementSettings s = base;
    s.incident = cases[i].first;
    s.angle_deg = cases[i].second;
    const auto m = measure_lysmer_reflection(s);
    std::printf(
        "  {\"incident\": \"%s\", \"angle_deg\": %g, \"R_P\": %s, \"R_S\": %s, "
        "\"energy_reflected\": %s, \"analytic_R_P\": %s, \"analytic_R_S\": %s, "
        "\"analytic_energy\": %s, \"n_dofs\": %zu, \"n_steps\": %zu, \"seconds\": %.2f}%s\n",
        s.incident == IncidentKind::p ? "P" : "SV", s.angle_deg, number(m.r_p).c_str(),
        number(m.r_s).c_str(), number(m.energy_reflected).c_str(),
        number(m.analytic.amplitude_p()).c_str(), number(m.analytic.amplitude_s()).c_str(),
        number(m.analytic.energy_reflected()).c_str(), m.n_dofs, m.n_steps, m.seconds,
        i + 1 < cases.size() ? "," : "");
    std::fflush(stdout);
  }
  std::printf("]\n");
  return 0;
}
