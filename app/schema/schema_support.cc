// The scene schema: rock support, the end-anchored bolts (dda/bolt.h, docs/support.md).
#include "app/schema/bound_sections.h"
#include "app/schema/schema_sections.h"
#include "dda/grouted_bolt.h"

namespace ddafem::schema
{
BoundKeys<dda::BoltDescription> bolt_keys()
{
  using S = dda::BoltDescription;
  using T = ValueType;
  BoundKeys<S> k;
  k.add(key("name", T::string).default_note("bolt<i>").meaning("unique name of its outputs"));
  k.add(key("head", T::vector2)
            .unit("m")
            .required()
            .meaning("the head: a point inside or on a block"));
  k.add(key("anchor", T::vector2)
            .unit("m")
            .required()
            .meaning("the anchor: a point inside or on another block than the head's"));
  k.field("area", &S::area)
      .unit("m^2")
      .required()
      .greater_than(0)
      .meaning("steel cross-section A_s");
  k.field("youngs_modulus", &S::youngs_modulus)
      .unit("Pa")
      .greater_than(0)
      .meaning("steel modulus E_s");
  k.field("yield_force", &S::yield_force)
      .unit("N")
      .required()
      .greater_than(0)
      .meaning("axial force at which it yields, perfectly plastic beyond");
  k.field("rupture_strain", &S::rupture_strain)
      .greater_than(0)
      .meaning("total elongation (L - L0) / L0 beyond which it breaks for good");
  k.field("pretension", &S::pretension)
      .unit("N")
      .at_least(0)
      .meaning("axial force at L = L0 as installed; below yield_force");
  k.field("type", &S::type)
      .meaning("end_anchored: attached at head and anchor only; grouted: bonded along "
               "its length, a spring (axial and dowel shear) at every block boundary it "
               "crosses (found at t = 0)");
  k.field("grout_modulus", &S::grout_modulus)
      .unit("Pa")
      .greater_than(0)
      .meaning("grouted: foundation modulus K of grout and rock around the bar (dowel "
               "stiffness K / (4 beta), beta = (K / (4 E_s I))^(1/4))");
  k.field("debonded_length", &S::debonded_length)
      .unit("m")
      .greater_than(0)
      .meaning("grouted: the bar's deformable length L_d across a joint; axial "
               "stiffness E_s A_s / L_d, rupture at rupture_strain x L_d");
  k.add(key("shear_capacity", T::number)
            .unit("N")
            .default_note("yield_force / sqrt(3)")
            .greater_than(0)
            .meaning("grouted: dowel force at which a crossing yields in shear"));
  return k;
}

Section bolts_section()
{
  return {"bolts[i]",
          "A rock bolt. End-anchored (default): a steel tendon attached to the block containing "
          "`head` and "
          "to the other block containing `anchor`, an axial spring between them that carries "
          "no compression, yields at `yield_force` and ruptures beyond `rupture_strain` "
          "(docs/support.md). Its axial force is N = pretension + k (L - L0 - plastic), "
          "k = youngs_modulus area / L0, L0 = |anchor - head| at t = 0. Grouted (`type: grouted`): "
          "bonded to every block it crosses; at each crossing an axial and a dowel spring that "
          "yield at `yield_force` and `shear_capacity` and rupture.",
          bolt_keys().keys()};
}

} // namespace ddafem::schema
