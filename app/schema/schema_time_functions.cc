// The scene schema: the time functions' variants.
#include "app/schema/bound_sections.h"
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

BoundKeys<SinePulseParameters> sine_pulse_keys()
{
  using S = SinePulseParameters;
  BoundKeys<S> k;
  k.add(time_function_type(TimeFunctionType::sine_pulse));
  k.field("frequency", &S::frequency).unit("Hz").required().greater_than(0).meaning("frequency");
  k.field("cycles", &S::cycles).greater_than(0).meaning("number of cycles");
  k.field("amplitude", &S::amplitude).meaning("peak value");
  k.field("start", &S::start).unit("s").meaning("time the pulse starts");
  return k;
}

Section sine_pulse_time_function_section()
{
  return {SceneSchema::time_function_section(TimeFunctionType::sine_pulse),
          "f(t) = amplitude sin(2 pi frequency (t - start)) for start <= t <= start + "
          "cycles / frequency, 0 elsewhere.",
          sine_pulse_keys().keys()};
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

BoundKeys<TableColumns> csv_keys()
{
  using S = TableColumns;
  using T = ValueType;
  BoundKeys<S> k;
  k.add(time_function_type(TimeFunctionType::csv));
  k.add(key("file", T::string)
            .required()
            .meaning("path of the CSV file, relative to the scene file's directory"));
  k.field("time_column", &S::time_column)
      .at_least(0)
      .meaning("column of the times [s], counted from 0");
  k.field("value_column", &S::value_column)
      .at_least(0)
      .meaning("column of the values, counted from 0");
  k.field("skip_rows", &S::skip_rows).at_least(0).meaning("header rows to skip");
  return k;
}

Section csv_time_function_section()
{
  return {SceneSchema::time_function_section(TimeFunctionType::csv),
          "A table read from a CSV file (comma-separated numbers; blank lines are ignored).",
          csv_keys().keys()};
}

} // namespace ddafem::schema

namespace ddafem::schema
{
namespace
{
/// How a record is cut, tapered, corrected, scaled and placed in the model's time.
void add_record_processing_keys(BoundKeys<RecordProcessing>& k)
{
  using S = RecordProcessing;
  using T = ValueType;
  k.add(key("from", T::number)
            .unit("s")
            .at_least(0)
            .default_note("0")
            .meaning("start of the part used, in the record's own time from its first sample"));
  k.add(key("to", T::number)
            .unit("s")
            .greater_than(0)
            .default_note("the record's end")
            .meaning("end of the part used"));
  k.add(key("taper", T::number)
            .unit("s")
            .at_least(0)
            .default_note("5 % of the part used, at most 0.5 s")
            .meaning("half-cosine taper of the acceleration at each end"));
  k.field("baseline", &S::baseline)
      .meaning("polynomial: the acceleration loses the least-squares polynomial that takes out "
               "the displacement's drift (t^2 to t^baseline_degree) with the velocity ending at "
               "0; none: as read");
  k.field("baseline_degree", &S::baseline_degree)
      .at_least(2)
      .at_most(8)
      .meaning("highest power of t in the displacement's baseline");
  k.add(key("scale", T::number).greater_than(0).default_note("1").meaning("factor on the record"));
  k.add(key("scale_to_pga", T::number)
            .unit("m/s^2")
            .greater_than(0)
            .meaning("scale the corrected record to this peak ground acceleration"));
  k.add(key("scale_to_pgv", T::number)
            .unit("m/s")
            .greater_than(0)
            .meaning("scale the corrected record to this peak ground velocity"));
  k.field("start", &S::start).unit("s").meaning("model time of the first sample used");
}
} // namespace

BoundKeys<RecordProcessing> record_keys()
{
  using S = RecordProcessing;
  using T = ValueType;
  BoundKeys<S> k;
  k.add(time_function_type(TimeFunctionType::record));
  k.add(key("file", T::string)
            .required()
            .meaning("path of the record, relative to the scene file's directory"));
  k.add(key("motion", T::choice)
            .choices(names_of<RecordMotion>())
            .required()
            .meaning("where it was recorded: outcrop (at a rock outcrop: the incident wave is "
                     "half of it), within (at depth in the free field: taken as the incident "
                     "wave; refused where the model has a free ground surface above the base) "
                     "or incident (the upgoing wave itself)"));
  k.add(key("format", T::choice)
            .choices(names_of<RecordFormat>())
            .default_note("peer for .AT2, .VT2 and .DT2 files, table otherwise")
            .meaning("peer: PEER NGA (4 header lines with the quantity, its units, NPTS and DT); "
                     "table: numbers separated by commas or blanks"));
  k.add(key("units", T::choice)
            .choices(names_of<RecordUnit>())
            .default_note("a PEER file's header; required for a table")
            .meaning("unit of the samples, which also says what they measure (g, m/s^2, cm/s^2: "
                     "acceleration; m/s, cm/s: velocity; m, cm: displacement)"));
  k.add(key("dt", T::number)
            .unit("s")
            .greater_than(0)
            .default_note("from the time column")
            .meaning("table: sampling interval; every number of every row is then a sample, in "
                     "row order"));
  k.field("time_column", &S::columns, &TableColumns::time_column)
      .at_least(0)
      .meaning("table: column of the times [s] (equal intervals), counted from 0");
  k.field("value_column", &S::columns, &TableColumns::value_column)
      .at_least(0)
      .meaning("table: column of the samples, counted from 0");
  k.field("skip_rows", &S::columns, &TableColumns::skip_rows)
      .at_least(0)
      .meaning("table: header rows");
  add_record_processing_keys(k);
  return k;
}

Section record_time_function_section()
{
  return {SceneSchema::time_function_section(TimeFunctionType::record),
          "A recorded ground motion (docs/ground_motions.md): a PEER NGA file or a table of "
          "acceleration, velocity or displacement, uniformly sampled. It is cut to [from, to], "
          "converted to acceleration, tapered at both ends, baseline-corrected and scaled, then "
          "integrated to the velocity (or displacement) the key asks for. An outcrop record "
          "gives an incident wave of half its motion. Its frequencies (tunnel.wave.frequency "
          "and max_frequency, the time-step advice) come from its Fourier spectrum, not its "
          "sampling.",
          record_keys().keys()};
}

} // namespace ddafem::schema
