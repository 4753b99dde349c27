// Prints measured and analytic Lysmer reflection coefficients as JSON (tools/verify_lysmer.py).
// Usage: lysmer_angles [--epw E] [--domain-factor F] [--margin M] [--runs N] [--steps S]
//                      [--tolerance T] [--frequency F0] [--trace FILE] [--case P|SV ANGLE]...
// Without --case: P and SV at 0, 15, 30, 45 and 60 degrees.
#include "tools/lysmer/lysmer_measurement.h"

#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <utility>
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

[[noreturn]] void usage()
{
  std::fprintf(stderr, "usage: lysmer_angles [--epw E] [--domain-factor F] [--margin M] "
                       "[--runs N] [--steps S] [--tolerance T] [--frequency F0] [--trace FILE] "
                       "[--case P|SV ANGLE]...\n");
  std::exit(2);
}

using namespace ddafem::fem;

/// The command line: settings shared by every case, the cases (incident, angle [deg]) and the
/// trace file (empty: none).
struct Arguments
{
  LysmerMeasurementSettings base;
  std::vector<std::pair<IncidentKind, double>> cases;
  std::string trace_file;
};

/// Sets the setting named by `key` to `value`; false if no setting has that name.
bool set_number(const std::string& key, const double value, LysmerMeasurementSettings& base)
{
  if (key == "--epw")
    base.elements_per_wavelength = value;
  else if (key == "--domain-factor")
    base.domain_factor = value;
  else if (key == "--margin")
    base.margin_periods = value;
  else if (key == "--runs")
    base.max_runs = static_cast<unsigned int>(value);
  else if (key == "--steps")
    base.steps_per_period = value;
  else if (key == "--tolerance")
    base.tolerance = value;
  else if (key == "--mesh-dispersion")
    base.mesh_dispersion = value != 0.0;
  else if (key == "--warp")
    base.warp_time = value != 0.0;
  else if (key == "--frequency")
    base.frequency = value;
  else
    return false;
  return true;
}

Arguments parse_arguments(const int argc, char** argv)
{
  Arguments args;
  for (int i = 1; i < argc; ++i)
  {
    const std::string key = argv[i];
    auto value = [&]() -> double
    {
      if (i + 1 >= argc)
        usage();
      return std::atof(argv[++i]);
    };
    if (key == "--trace" && i + 1 < argc)
    {
      args.trace_file = argv[++i];
      args.base.record_trace = true;
    }
    else if (key == "--case" && i + 2 < argc)
    {
      const std::string kind = argv[++i];
      if (kind != "P" && kind != "SV")
        usage();
      args.cases.emplace_back(kind == "P" ? IncidentKind::p : IncidentKind::sv, value());
    }
    else if (!set_number(key, value(), args.base))
      usage();
  }
  if (args.cases.empty())
    for (const auto kind : {IncidentKind::p, IncidentKind::sv})
      for (const double angle : {0.0, 15.0, 30.0, 45.0, 60.0})
        args.cases.emplace_back(kind, angle);
  return args;
}

/// Appends "incident angle run t v_x v_y fit_x fit_y" lines to the trace file.
void append_trace(const std::string& trace_file, const LysmerMeasurementSettings& s,
                  const LysmerMeasurement& m)
{
  if (std::FILE* f = std::fopen(trace_file.c_str(), "a"))
  {
    for (std::size_t r = 0; r < m.runs.size(); ++r)
      for (const auto& row : m.runs[r].trace)
        std::fprintf(f, "%s %g %zu %.6e %.6e %.6e %.6e %.6e\n",
                     s.incident == IncidentKind::p ? "P" : "SV", s.angle_deg, r, row[0], row[1],
                     row[2], row[3], row[4]);
    std::fclose(f);
  }
}

/// The runs of a measurement as a JSON list.
std::string runs_json(const LysmerMeasurement& m)
{
  std::string runs = "[";
  for (std::size_t r = 0; r < m.runs.size(); ++r)
  {
    char buffer[200];
    std::snprintf(buffer, sizeof buffer,
                  "%s{\"R_P\": %s, \"R_S\": %s, \"rms_residual\": %.6f, \"incident\": %.6f}",
                  r > 0 ? ", " : "", number(m.runs[r].r_p).c_str(), number(m.runs[r].r_s).c_str(),
                  m.runs[r].rms_residual, m.runs[r].incident);
    runs += buffer;
    runs.pop_back();
    runs += ", \"coefficients\": [";
    for (std::size_t w = 0; w < m.runs[r].coefficients.size(); ++w)
    {
      std::snprintf(buffer, sizeof buffer, "%s[%.6f, %.6f]", w > 0 ? ", " : "",
                    m.runs[r].coefficients[w][0], m.runs[r].coefficients[w][1]);
      runs += buffer;
    }
    runs += "]}";
  }
  runs += "]";
  return runs;
}

/// One case as a JSON object (followed by a comma unless it is the last).
void print_case(const LysmerMeasurementSettings& s, const LysmerMeasurement& m, const bool last)
{
  std::printf("  {\"incident\": \"%s\", \"angle_deg\": %g, \"R_P\": %s, \"R_S\": %s, "
              "\"energy_reflected\": %s, \"analytic_R_P\": %s, \"analytic_R_S\": %s, "
              "\"analytic_energy\": %s, \"n_dofs\": %zu, \"n_steps\": %zu, \"seconds\": %.2f, "
              "\"domain\": [%.1f, %.1f, %.1f], \"monitor_height\": %.1f, \"window\": [%.4f, %.4f], "
              "\"runs\": %s}%s\n",
              s.incident == IncidentKind::p ? "P" : "SV", s.angle_deg, number(m.r_p).c_str(),
              number(m.r_s).c_str(), number(m.energy_reflected).c_str(),
              number(m.analytic.amplitude_p()).c_str(), number(m.analytic.amplitude_s()).c_str(),
              number(m.analytic.energy_reflected()).c_str(), m.n_dofs, m.n_steps, m.seconds,
              m.domain[0], m.domain[1], m.domain[2], m.monitor_height, m.window[0], m.window[1],
              runs_json(m).c_str(), last ? "" : ",");
  std::fflush(stdout);
}
} // namespace

int main(int argc, char** argv)
{
  const Arguments args = parse_arguments(argc, argv);
  std::printf("[\n");
  for (std::size_t i = 0; i < args.cases.size(); ++i)
  {
    LysmerMeasurementSettings s = args.base;
    s.incident = args.cases[i].first;
    s.angle_deg = args.cases[i].second;
    const auto m = measure_lysmer_reflection(s);
    if (!args.trace_file.empty())
      append_trace(args.trace_file, s, m);
    print_case(s, m, i + 1 == args.cases.size());
  }
  std::printf("]\n");
  return 0;
}
