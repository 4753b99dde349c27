// The scene schema: rock support, the end-anchored bolts (dda/bolt.h, docs/support.md).
#include "app/schema/schema_sections.h"
#include "dda/grouted_bolt.h"

namespace ddafem::schema
{
Section bolts_section()
{
  using T = ValueType;
  return {"bolts[i]",
          "A rock bolt. End-anchored (default): a steel tendon attached to the block containing "
          "`head` and "
          "to the other block containing `anchor`, an axial spring between them that carries "
          "no compression, yields at `yield_force` and ruptures beyond `rupture_strain` "
          "(docs/support.md). Its axial force is N = pretension + k (L - L0 - plastic), "
          "k = youngs_modulus area / L0, L0 = |anchor - head| at t = 0. Grouted (`type: grouted`): "
          "bonded to every block it crosses; at each crossing an axial and a dowel spring that "
          "yield at `yield_force` and `shear_capacity` and rupture.",
          {key("name", T::string).default_note("bolt<i>").meaning("unique name of its outputs"),
           key("head", T::vector2)
               .unit("m")
               .required()
               .meaning("the head: a point inside or on a block"),
           key("anchor", T::vector2)
               .unit("m")
               .required()
               .meaning("the anchor: a point inside or on another block than the head's"),
           key("area", T::number)
               .unit("m^2")
               .required()
               .greater_than(0)
               .meaning("steel cross-section A_s"),
           key("youngs_modulus", T::number)
               .unit("Pa")
               .default_yaml("200e9")
               .greater_than(0)
               .meaning("steel modulus E_s"),
           key("yield_force", T::number)
               .unit("N")
               .required()
               .greater_than(0)
               .meaning("axial force at which it yields, perfectly plastic beyond"),
           key("rupture_strain", T::number)
               .default_yaml("0.1")
               .greater_than(0)
               .meaning("total elongation (L - L0) / L0 beyond which it breaks for good"),
           key("pretension", T::number)
               .unit("N")
               .default_yaml("0")
               .at_least(0)
               .meaning("axial force at L = L0 as installed; below yield_force"),
           key("type", T::choice)
               .default_yaml("end_anchored")
               .choices(names_of<dda::BoltType>())
               .meaning("end_anchored: attached at head and anchor only; grouted: bonded along "
                        "its length, a spring (axial and dowel shear) at every block boundary it "
                        "crosses (found at t = 0)"),
           key("grout_modulus", T::number)
               .unit("Pa")
               .default_yaml("10e9")
               .greater_than(0)
               .meaning("grouted: foundation modulus K of grout and rock around the bar (dowel "
                        "stiffness K / (4 beta), beta = (K / (4 E_s I))^(1/4))"),
           key("debonded_length", T::number)
               .unit("m")
               .default_yaml("0.3")
               .greater_than(0)
               .meaning("grouted: the bar's deformable length L_d across a joint; axial "
                        "stiffness E_s A_s / L_d, rupture at rupture_strain x L_d"),
           key("shear_capacity", T::number)
               .unit("N")
               .default_note("yield_force / sqrt(3)")
               .greater_than(0)
               .meaning("grouted: dowel force at which a crossing yields in shear")}};
}

} // namespace ddafem::schema
