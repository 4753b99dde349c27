// The scene schema: the lining (dda/lining.h, docs/support.md "Lining"), of block scenes
// (`linings[i]`) and of the tunnel (`tunnel.lining`).
#include "app/schema/bound_sections.h"
#include "app/schema/schema_sections.h"

namespace ddafem::schema
{
/// The section and strength keys both share.
BoundKeys<dda::LiningDescription> lining_section_keys()
{
  using S = dda::LiningDescription;
  BoundKeys<S> k;
  k.field("segment_length", &S::segment_length)
      .unit("m")
      .required()
      .greater_than(0)
      .meaning("largest element length: each leg is split into equal elements no longer; an "
               "element that straddles a joint bridges it over this length");
  k.field("thickness", &S::thickness).unit("m").required().greater_than(0).meaning("t");
  k.field("youngs_modulus", &S::youngs_modulus)
      .unit("Pa")
      .greater_than(0)
      .meaning("E of the shotcrete or concrete");
  k.field("compressive_strength", &S::compressive_strength)
      .unit("Pa")
      .required()
      .greater_than(0)
      .meaning("f_c: the fibre stress may not fall below -f_c");
  k.field("tensile_strength", &S::tensile_strength)
      .unit("Pa")
      .required()
      .greater_than(0)
      .meaning("f_t (flexural): the fibre stress may not exceed f_t");
  k.field("shear_strength", &S::shear_strength)
      .unit("Pa")
      .at_least(0)
      .meaning("f_v: 1.5 |V| / t may not exceed it; 0: not checked");
  return k;
}

namespace
{
const char* const law_text =
    "2D Euler-Bernoulli frame elements of thickness `thickness` (unit width) between nodes at "
    "most `segment_length` apart; each node is a material point of the block it lies on and "
    "turns with it. An element between two blocks couples them; one on a single block moves "
    "with it. An element whose extreme-fibre stress N/t +- 6M/t^2 exceeds the tensile or "
    "compressive strength (or whose shear stress 1.5 V/t exceeds `shear_strength`) breaks for "
    "good (docs/support.md).";
} // namespace

BoundKeys<dda::LiningDescription> lining_path_keys()
{
  using S = dda::LiningDescription;
  using T = ValueType;
  BoundKeys<S> k;
  k.add(key("name", T::string).default_note("lining<i>").meaning("unique name of its outputs"));
  k.add(key("points", T::point_list)
            .unit("m")
            .default_note("none: give `opening`")
            .meaning("the polyline, at least two points; every node on or inside a block"));
  k.field("closed", &S::closed).meaning("the last point of `points` joins the first (a ring)");
  k.add(key("opening", T::integer)
            .default_note("none: give `points`")
            .at_least(0)
            .meaning("instead of `points`: around the boundary of rock_mass.openings[opening] as "
                     "excavated, closed"));
  k.add(key("installed_after", T::string)
            .default_note("from the start")
            .meaning("the name of the stage after which it is installed: it carries what "
                     "happens from the next stage on"));
  return k;
}

Section linings_section()
{
  std::vector<Key> keys = lining_path_keys().keys();
  for (Key& k : lining_section_keys().keys())
    keys.push_back(std::move(k));
  return {"linings[i]",
          std::string("A lining of shotcrete or concrete on the blocks' surface along `points` "
                      "or around an opening: ") +
              law_text,
          keys};
}

Section tunnel_lining_section()
{
  return {"tunnel.lining",
          std::string("A lining around the whole opening as excavated (`linings[i]` with "
                      "`opening: 0`, named `lining`), installed after the static excavation "
                      "stage: it carries the dynamic increment only, the rock having taken the "
                      "excavation's load. ") +
              law_text,
          lining_section_keys().keys()};
}

} // namespace ddafem::schema
