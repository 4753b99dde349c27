#include "app/scene/record_reader.h"

#include "app/scene/scene_text.h"
#include "app/schema/bound_sections.h"
#include "app/schema/scene_schema.h"
#include "common/format.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>

namespace ddafem::scene_reading
{
std::filesystem::path scene_file(const MapReader& r, const std::string& key,
                                 const std::string& what)
{
  std::filesystem::path path(r.string(key));
  if (path.is_relative())
    path = r.ctx().scene_directory / path;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw r.error(key, "cannot open " + what + " '" + path.lexically_normal().string() +
                           "': expected a regular file");
  return path;
}

namespace
{
using schema::RecordFormat;
using schema::RecordUnit;

/// The samples of a record as the file gives them.
struct RawRecord
{
  std::vector<double> samples;
  double dt = 0.0;
  RecordUnit unit = RecordUnit::g;
  bool unit_known = false; ///< the file says its unit (PEER)
};

MotionQuantity quantity_of(RecordUnit unit)
{
  switch (unit)
  {
  case RecordUnit::g:
  case RecordUnit::m_per_s2:
  case RecordUnit::cm_per_s2:
    return MotionQuantity::acceleration;
  case RecordUnit::m_per_s:
  case RecordUnit::cm_per_s:
    return MotionQuantity::velocity;
  case RecordUnit::m:
  case RecordUnit::cm:
    break;
  }
  return MotionQuantity::displacement;
}

/// SI value of one unit.
double si_factor(RecordUnit unit)
{
  switch (unit)
  {
  case RecordUnit::g:
    return standard_gravity;
  case RecordUnit::cm_per_s2:
  case RecordUnit::cm_per_s:
  case RecordUnit::cm:
    return 0.01;
  case RecordUnit::m_per_s2:
  case RecordUnit::m_per_s:
  case RecordUnit::m:
    break;
  }
  return 1.0;
}

std::string upper(std::string s)
{
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return s;
}

/// The unit a PEER header's third line names after "UNITS OF" ("G", "CM/S/S", "CM/S", "CM").
std::optional<RecordUnit> peer_unit(const std::string& line, MotionQuantity quantity)
{
  static const std::regex units(R"(UNITS\s+OF\s+([A-Z0-9/\^]+))");
  std::smatch m;
  const std::string text = upper(line);
  if (!std::regex_search(text, m, units))
    return std::nullopt;
  const std::string u = m[1].str();
  if (quantity == MotionQuantity::acceleration)
  {
    if (u == "G")
      return RecordUnit::g;
    if (u == "CM/S/S" || u == "CM/S^2" || u == "CM/S2" || u == "CM/SEC/SEC" || u == "GAL")
      return RecordUnit::cm_per_s2;
    if (u == "M/S/S" || u == "M/S^2" || u == "M/S2")
      return RecordUnit::m_per_s2;
  }
  else if (quantity == MotionQuantity::velocity)
  {
    if (u == "CM/S" || u == "CM/SEC")
      return RecordUnit::cm_per_s;
    if (u == "M/S" || u == "M/SEC")
      return RecordUnit::m_per_s;
  }
  else if (u == "CM" || u == "M")
    return u == "CM" ? RecordUnit::cm : RecordUnit::m;
  return std::nullopt;
}

/// A PEER NGA file: line 3 names the quantity and its units, line 4 NPTS and DT (as
/// "NPTS= 4000, DT= .0100 SEC" or, in older files, "4000 0.0100 NPTS, DT"), the samples follow.
RawRecord read_peer(const MapReader& r, const std::filesystem::path& path)
{
  const std::string shown = path.lexically_normal().string();
  std::ifstream in(path);
  std::vector<std::string> header(4);
  for (std::string& line : header)
    if (!std::getline(in, line))
      throw r.error("file", "PEER file '" + shown + "' ends inside its 4 header lines");
  const auto at_line = [&](int line, const std::string& what) {
    return r.error("file", "PEER file '" + shown + "' line " + std::to_string(line) + ": " + what);
  };

  const std::string kind = upper(header[2]);
  MotionQuantity quantity = MotionQuantity::acceleration;
  if (kind.find("VELOCITY") != std::string::npos)
    quantity = MotionQuantity::velocity;
  else if (kind.find("DISPLACEMENT") != std::string::npos)
    quantity = MotionQuantity::displacement;
  else if (kind.find("ACCELERATION") == std::string::npos)
    throw at_line(3, "found '" + trim(header[2]) +
                         "', expected ACCELERATION, VELOCITY or DISPLACEMENT and its units");
  RawRecord raw;
  const std::optional<RecordUnit> unit = peer_unit(header[2], quantity);
  if (!unit)
    throw at_line(3, "found '" + trim(header[2]) + "', expected 'UNITS OF' and a unit of " +
                         name_of(quantity) + " (G, CM/S/S; CM/S; CM)");
  raw.unit = *unit;
  raw.unit_known = true;

  // At most 9 digits: a count that fits, and that stoul reads.
  static const std::regex new_form(R"(NPTS\s*=\s*(\d{1,9})\s*,?\s*DT\s*=\s*([0-9.eE+-]+))");
  static const std::regex old_form(R"(^\s*(\d{1,9})\s+([0-9.eE+-]+)\s+NPTS)");
  std::smatch m;
  const std::string counts = upper(header[3]);
  if (!std::regex_search(counts, m, new_form) && !std::regex_search(counts, m, old_form))
    throw at_line(4, "found '" + trim(header[3]) + "', expected 'NPTS= n, DT= dt SEC'");
  const std::size_t npts = std::stoul(m[1].str());
  const std::optional<double> dt = parse_double(m[2].str());
  if (!dt || !(*dt > 0.0))
    throw at_line(4, "DT is '" + m[2].str() + "', expected a number > 0");
  raw.dt = *dt;

  std::string line;
  for (int number = 5; std::getline(in, line); ++number)
  {
    std::istringstream words(line);
    std::string word;
    while (words >> word)
    {
      const std::optional<double> x = parse_double(word);
      if (!x)
        throw at_line(number, "'" + word + "' is not a number");
      raw.samples.push_back(*x);
    }
  }
  if (raw.samples.size() != npts)
    throw r.error("file", "PEER file '" + shown + "' has " + std::to_string(raw.samples.size()) +
                              " samples, its header says NPTS= " + std::to_string(npts));
  return raw;
}

/// The numbers of one table row, separated by commas or blanks.
std::vector<std::string> cells_of(const std::string& line)
{
  std::string spaced = line;
  std::replace(spaced.begin(), spaced.end(), ',', ' ');
  std::istringstream words(spaced);
  std::vector<std::string> cells;
  for (std::string w; words >> w;)
    cells.push_back(w);
  return cells;
}

/// A table: a time column and a value column, or (with `dt`) samples in row order.
RawRecord read_table(const MapReader& r, const std::filesystem::path& path,
                     const schema::TableColumns& columns)
{
  const std::string shown = path.lexically_normal().string();
  const bool fixed_dt = r.has("dt");
  if (fixed_dt && (r.has("time_column") || r.has("value_column")))
    throw r.error("dt", "with a fixed dt every number of a row is a sample: expected no "
                        "time_column or value_column");
  const auto time_column = static_cast<std::size_t>(columns.time_column);
  const auto value_column = static_cast<std::size_t>(columns.value_column);
  const long long skip_rows = columns.skip_rows;
  RawRecord raw;
  std::vector<double> times;
  std::ifstream in(path);
  std::string line;
  for (long long row = 1; std::getline(in, line); ++row)
  {
    if (row <= skip_rows)
      continue;
    const std::vector<std::string> cells = cells_of(line);
    const std::string at_row = "table '" + shown + "' row " + std::to_string(row) + ": ";
    const auto number = [&](const std::string& text)
    {
      const std::optional<double> x = parse_double(text);
      if (!x)
        throw r.error("file", at_row + "'" + text + "' is not a number");
      return *x;
    };
    if (fixed_dt)
      for (const std::string& c : cells)
        raw.samples.push_back(number(c));
    else if (!cells.empty())
    {
      if (cells.size() <= std::max(time_column, value_column))
        throw r.error("file", at_row + "found " + std::to_string(cells.size()) +
                                  " column(s), expected at least " +
                                  std::to_string(std::max(time_column, value_column) + 1));
      times.push_back(number(cells[time_column]));
      raw.samples.push_back(number(cells[value_column]));
    }
  }
  if (raw.samples.size() < 3)
    throw r.error("file", "table '" + shown + "' has " + std::to_string(raw.samples.size()) +
                              " sample(s) after skipping " + std::to_string(skip_rows) +
                              " row(s), expected at least 3");
  if (fixed_dt)
  {
    raw.dt = r.number("dt");
    return raw;
  }
  const double first = times[1] - times[0];
  for (std::size_t i = 1; i < times.size(); ++i)
    if (!(std::abs(times[i] - times[i - 1] - first) <= 1e-3 * first))
      throw r.error("file", "table '" + shown + "': the times are not uniformly sampled: " +
                                format_number(times[i - 1]) + " to " + format_number(times[i]) +
                                " s after intervals of " + format_number(first) +
                                " s (expected equal intervals > 0 within 0.1 %)");
  raw.dt = (times.back() - times.front()) / static_cast<double>(times.size() - 1);
  return raw;
}

/// The record's samples as the file gives them, and its unit.
RawRecord read_raw(const MapReader& r, const schema::TableColumns& columns)
{
  const std::filesystem::path path = scene_file(r, "file", "record file");
  // At least 2 characters a sample; each sample becomes a handful of doubles (the samples, the
  // acceleration, its integrals, the spectrum): 4 x the file's size bounds it.
  std::error_code ec;
  const double bytes = 4.0 * static_cast<double>(std::filesystem::file_size(path, ec));
  if (!r.ctx().limits.fits(bytes))
    throw r.error("file", "the record '" + path.lexically_normal().string() + "' would need " +
                              r.ctx().limits.too_much(bytes) + ": expected a smaller file");
  std::string extension = upper(path.extension().string());
  const bool peer_name = extension == ".AT2" || extension == ".VT2" || extension == ".DT2";
  const RecordFormat format = r.has("format")
                                  ? r.choice_of<RecordFormat>("format")
                                  : (peer_name ? RecordFormat::peer : RecordFormat::table);
  if (format == RecordFormat::peer)
    for (const char* key : {"dt", "time_column", "value_column", "skip_rows"})
      if (r.has(key))
        throw r.error(key, std::string("a PEER file gives its own layout: expected no `") + key +
                               "` with format peer");
  if (format == RecordFormat::table && !r.has("units"))
    throw r.error("units", "a table does not say what it measures: expected `units` (" +
                               join(names_of<RecordUnit>(), ", ") + ")");
  RawRecord raw = format == RecordFormat::peer ? read_peer(r, path) : read_table(r, path, columns);
  if (raw.unit_known && r.has("units") && r.choice_of<RecordUnit>("units") != raw.unit)
    throw r.error("units", std::string("the file's header says its samples are in ") +
                               name_of(raw.unit) + ": expected that, or no `units`");
  if (!raw.unit_known)
    raw.unit = r.choice_of<RecordUnit>("units");
  if (raw.samples.size() < 3)
    throw r.error("file",
                  "expected at least 3 samples, found " + std::to_string(raw.samples.size()));
  return raw;
}

/// The window [from, to] of the record's own time as sample indices [first, last].
std::array<std::size_t, 2> window_of(const MapReader& r, const RawRecord& raw)
{
  const double length = raw.dt * static_cast<double>(raw.samples.size() - 1);
  const double from = r.has("from") ? r.number("from") : 0.0;
  const double to = r.has("to") ? r.number("to") : length;
  if (from >= length)
    throw r.error("from",
                  "expected a time before the record's end (" + format_number(length) + " s)");
  if (to <= from || to > length * (1.0 + 1e-12))
    throw r.error("to", "expected a time after `from` (" + format_number(from) +
                            " s) and at most the record's length (" + format_number(length) +
                            " s)");
  const auto first = static_cast<std::size_t>(std::llround(from / raw.dt));
  const auto last =
      std::min(raw.samples.size() - 1, static_cast<std::size_t>(std::llround(to / raw.dt)));
  if (last < first + 2)
    throw r.error("to", "the window holds fewer than 3 samples: expected a longer window");
  return {first, last};
}

/// Scale factor from `scale`, `scale_to_pga` or `scale_to_pgv` (at most one).
double scale_of(const MapReader& r, const MotionSummary& unscaled)
{
  const int given = int(r.has("scale")) + int(r.has("scale_to_pga")) + int(r.has("scale_to_pgv"));
  if (given > 1)
    throw r.error("scale", "expected at most one of scale, scale_to_pga and scale_to_pgv");
  if (r.has("scale_to_pga"))
    return r.number("scale_to_pga") / unscaled.pga;
  if (r.has("scale_to_pgv"))
    return r.number("scale_to_pgv") / unscaled.pgv;
  return r.has("scale") ? r.number("scale") : 1.0;
}
} // namespace

TimeFunction read_record(const MapReader& r, TimeFunctionUse use)
{
  schema::RecordProcessing processing;
  schema::record_keys().fill(r, processing);
  const RawRecord raw = read_raw(r, processing.columns);
  const auto [first, last] = window_of(r, raw);
  std::vector<double> si(raw.samples.begin() + static_cast<std::ptrdiff_t>(first),
                         raw.samples.begin() + static_cast<std::ptrdiff_t>(last) + 1);
  for (double& x : si)
    x *= si_factor(raw.unit);
  std::vector<double> a = to_acceleration(si, raw.dt, quantity_of(raw.unit));

  RecordInfo info;
  info.file = r.string("file");
  info.motion = r.choice_of<RecordMotion>("motion");
  info.dt = raw.dt;
  info.window_from = raw.dt * static_cast<double>(first);
  info.window_to = raw.dt * static_cast<double>(last);
  info.start = processing.start;
  const double window = info.window_to - info.window_from;
  const double taper = r.has("taper") ? r.number("taper") : std::min(0.5, 0.05 * window);
  taper_ends(a, raw.dt, taper);
  if (processing.baseline == schema::BaselineMethod::polynomial)
    info.baseline =
        correct_baseline(a, raw.dt, static_cast<int>(processing.baseline_degree), taper);
  const MotionSummary unscaled = summarize_motion(a, raw.dt);
  if (!(unscaled.pga > 0.0))
    throw r.error("file", "the record's window is at rest (zero acceleration): expected motion");
  info.scale = scale_of(r, unscaled);
  for (double& x : a)
    x *= info.scale;
  info.summary = summarize_motion(a, raw.dt);

  std::vector<double> values = integrate(a, raw.dt);
  if (use == TimeFunctionUse::displacement)
    values = integrate(values, raw.dt);
  std::vector<double> times(values.size());
  const double factor = incident_factor(info.motion);
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    times[i] = info.start + raw.dt * static_cast<double>(i);
    values[i] *= factor;
  }
  return TimeFunction::record(std::move(times), std::move(values), std::move(info));
}

} // namespace ddafem::scene_reading
