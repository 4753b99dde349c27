// The scene schema: `tunnel.bolts`, a pattern of radial bolts from the opening's surface
// (app/scene/tunnel_bolts.h, docs/support.md). Each generated bolt has the keys of `bolts[i]` but
// its name and ends.
#include "app/schema/bound_sections.h"
#include "app/schema/schema_sections.h"

#include <algorithm>

namespace ddafem::schema
{
BoundKeys<BoltPattern> tunnel_bolt_pattern_keys()
{
  using S = BoltPattern;
  using T = ValueType;
  BoundKeys<S> k;
  k.field("length", &S::length)
      .unit("m")
      .required()
      .greater_than(0)
      .meaning("of each bolt, from its head on the opening's surface into the rock");
  k.add(key("count", T::integer)
            .default_note("(give count or spacing)")
            .greater_than(0)
            .meaning("number of bolts, equally spaced in angle from from_angle to to_angle"));
  k.add(key("spacing", T::number)
            .unit("m")
            .default_note("(give count or spacing)")
            .greater_than(0)
            .meaning("along the opening's perimeter: count = round(perimeter between the "
                     "angles / spacing) + 1"));
  k.field("from_angle", &S::from_angle)
      .unit("deg")
      .meaning("first bolt's direction, anticlockwise from +x about the opening's centre (90: "
               "the crown)");
  k.field("to_angle", &S::to_angle)
      .unit("deg")
      .meaning("last bolt's direction (from_angle < to_angle <= from_angle + 360)");
  return k;
}

Section tunnel_bolts_section()
{
  std::vector<Key> keys = tunnel_bolt_pattern_keys().keys();
  for (const Key& k : bolts_section().keys)
    if (k.name != "name" && k.name != "head" && k.name != "anchor")
      keys.push_back(k);
  return {"tunnel.bolts",
          "A pattern of radial rock bolts installed at the excavation: from the opening's centre "
          "(a circle's centre, a horseshoe's roof centre, a polygon's box centre) at angles "
          "from_angle to to_angle, each from its head where the ray leaves the opening to an "
          "anchor `length` further. They become `bolts` entries named tunnel_bolt<i>_<angle>deg "
          "with the keys below (as in `bolts[i]`), act from the start of the static excavation "
          "stage and are refused, like any bolt, if one does not reach a second block.",
          keys};
}

} // namespace ddafem::schema
