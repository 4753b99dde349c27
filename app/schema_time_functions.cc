// The scene schema: the time functions' variants.
#include "app/schema_sections.h"

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
