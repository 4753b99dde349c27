// The scene schema: the time functions' variants.
#include "app/schema/schema_sections.h"
#include "common/ground_motion.h"

#include <vector>

namespace ddafem::schema
{
Section constant_time_function_section()
{
  using T = ValueType;
  return {SceneSchema::time_function_section(TimeFunctionType::constant),
          "f(t) = value.",
          {time_function_type(TimeFunctionType::constant),
           key("value", T::number)
               .required()
               .meaning("the constant (in the unit of the quantity it gives)")}};
}

Section sine_pulse_time_function_section()
{
  using T = ValueType;
  return {SceneSchema::time_function_section(TimeFunctionType::sine_pulse),
          "f(t) = amplitude sin(2 pi frequency (t - start)) for start <= t <= start + "
          "cycles / frequency, 0 elsewhere.",
          {time_function_type(TimeFunctionType::sine_pulse),
           key("frequency", T::number).unit("Hz").required().greater_than(0).meaning("frequency"),
           key("cycles", T::number).default_yaml("1").greater_than(0).meaning("number of cycles"),
           key("amplitude", T::number).default_yaml("1").meaning("peak value"),
           key("start", T::number).unit("s").default_yaml("0").meaning("time the pulse starts")}};
}

Section table_time_function_section()
{
  using T = ValueType;
  return {SceneSchema::time_function_section(TimeFunctionType::table),
          "Piecewise-linear interpolation of (time, value) points; the first value holds before "
          "the first time and the last value after the last time.",
          {time_function_type(TimeFunctionType::table),
           key("points", T::table)
               .unit("s, -")
               .required()
               .meaning("[[t, value], ...] with strictly increasing t, at least one point")}};
}

Section csv_time_function_section()
{
  using T = ValueType;
  return {
      SceneSchema::time_function_section(TimeFunctionType::csv),
      "A table read from a CSV file (comma-separated numbers; blank lines are ignored).",
      {time_function_type(TimeFunctionType::csv),
       key("file", T::string)
           .required()
           .meaning("path of the CSV file, relative to the scene file's directory"),
       key("time_column", T::integer)
           .default_yaml("0")
           .at_least(0)
           .meaning("column of the times [s], counted from 0"),
       key("value_column", T::integer)
           .default_yaml("1")
           .at_least(0)
           .meaning("column of the values, counted from 0"),
       key("skip_rows", T::integer).default_yaml("0").at_least(0).meaning("header rows to skip")}};
}

} // namespace ddafem::schema

namespace ddafem::schema
{
namespace
{
/// How a record is cut, tapered, corrected, scaled and placed in the model's time.
std::vector<Key> record_processing_keys()
{
  using T = ValueType;
  return {key("from", T::number)
              .unit("s")
              .at_least(0)
              .default_note("0")
              .meaning("start of the part used, in the record's own time from its first sample"),
          key("to", T::number)
              .unit("s")
              .greater_than(0)
              .default_note("the record's end")
              .meaning("end of the part used"),
          key("taper", T::number)
              .unit("s")
              .at_least(0)
              .default_note("5 % of the part used, at most 0.5 s")
              .meaning("half-cosine taper of the acceleration at each end"),
          key("baseline", T::choice)
              .choices(names_of<BaselineMethod>())
              .default_yaml("polynomial")
              .meaning("polynomial: the acceleration loses the least-squares polynomial that "
                       "takes out the displacement's drift (t^2 to t^baseline_degree) with the "
                       "velocity ending at 0; none: as read"),
          key("baseline_degree", T::integer)
              .default_yaml("3")
              .at_least(2)
              .at_most(8)
              .meaning("highest power of t in the displacement's baseline"),
          key("scale", T::number).greater_than(0).default_note("1").meaning("factor on the record"),
          key("scale_to_pga", T::number)
              .unit("m/s^2")
              .greater_than(0)
              .meaning("scale the corrected record to this peak ground acceleration"),
          key("scale_to_pgv", T::number)
              .unit("m/s")
              .greater_than(0)
              .meaning("scale the corrected record to this peak ground velocity"),
          key("start", T::number)
              .unit("s")
              .default_yaml("0")
              .meaning("model time of the first sample used")};
}
} // namespace

Section record_time_function_section()
{
  using T = ValueType;
  Section section{
      SceneSchema::time_function_section(TimeFunctionType::record),
      "A recorded ground motion (docs/ground_motions.md): a PEER NGA file or a table of "
      "acceleration, velocity or displacement, uniformly sampled. It is cut to [from, to], "
      "converted to acceleration, tapered at both ends, baseline-corrected and scaled, then "
      "integrated to the velocity (or displacement) the key asks for. An outcrop record gives "
      "an incident wave of half its motion. Its frequencies (tunnel.wave.frequency and "
      "max_frequency, the time-step advice) come from its Fourier spectrum, not its sampling.",
      {time_function_type(TimeFunctionType::record),
       key("file", T::string)
           .required()
           .meaning("path of the record, relative to the scene file's directory"),
       key("motion", T::choice)
           .choices(names_of<RecordMotion>())
           .required()
           .meaning("where it was recorded: outcrop (at a rock outcrop: the incident wave is "
                    "half of it), within (at depth in the free field: taken as the incident "
                    "wave; refused where the model has a free ground surface above the base) "
                    "or incident (the upgoing wave itself)"),
       key("format", T::choice)
           .choices(names_of<RecordFormat>())
           .default_note("peer for .AT2, .VT2 and .DT2 files, table otherwise")
           .meaning("peer: PEER NGA (4 header lines with the quantity, its units, NPTS and DT); "
                    "table: numbers separated by commas or blanks"),
       key("units", T::choice)
           .choices(names_of<RecordUnit>())
           .default_note("a PEER file's header; required for a table")
           .meaning("unit of the samples, which also says what they measure (g, m/s^2, cm/s^2: "
                    "acceleration; m/s, cm/s: velocity; m, cm: displacement)"),
       key("dt", T::number)
           .unit("s")
           .greater_than(0)
           .default_note("from the time column")
           .meaning("table: sampling interval; every number of every row is then a sample, in "
                    "row order"),
       key("time_column", T::integer)
           .default_yaml("0")
           .at_least(0)
           .meaning("table: column of the times [s] (equal intervals), counted from 0"),
       key("value_column", T::integer)
           .default_yaml("1")
           .at_least(0)
           .meaning("table: column of the samples, counted from 0"),
       key("skip_rows", T::integer).default_yaml("0").at_least(0).meaning("table: header rows")}};
  const std::vector<Key> processing = record_processing_keys();
  section.keys.insert(section.keys.end(), processing.begin(), processing.end());
  return section;
}

} // namespace ddafem::schema
