// The scene schema of the rock's damping (dda/damping.h): `materials.<name>.damping`,
// `joint_materials.<name>.damping` and the tunnels' default `tunnel.damping`.
#include "app/schema/schema_sections.h"

namespace ddafem::schema
{
Key damping_key(const std::string& section_id, const std::string& what)
{
  return key("damping", ValueType::section)
      .section(section_id)
      .default_note(section_id == "tunnel.damping" ? "ratio 0.02 at the wave's frequency"
                                                   : "none: undamped")
      .meaning("stiffness-proportional damping of " + what +
               ": a dashpot beta K beside each stiffness K, beta = ratio / (pi frequency)");
}

Section damping_section(const std::string& id)
{
  using T = ValueType;
  return {id,
          "Damping of the rock: dashpots C = beta K beside the blocks' elasticity (on strain "
          "rates), the bonded joints' springs and the closed contacts' normal springs (the shear "
          "spring's while a contact sticks; never on a sliding contact's slip), beta = ratio / "
          "(pi frequency). A mode of frequency f has the damping ratio ratio x f / frequency: "
          "exact at `frequency`, half of it an octave below, twice it an octave above. Rigid-body "
          "motion (a falling or sliding block) is not damped, and it does not depend on dt "
          "(docs/damping.md).",
          {key("ratio", T::number)
               .default_note(id == "tunnel.damping" ? "0.02" : "required")
               .at_least(0)
               .less_than(1)
               .meaning("fraction of critical damping at `frequency`, e.g. 0.02; 0: undamped"),
           key("frequency", T::number)
               .unit("Hz")
               .greater_than(0)
               .default_note("the dominant frequency of the scene's input: the tunnel's wave, a "
                             "boundary's or the far field's incident motion")
               .meaning("where the ratio holds")}};
}

} // namespace ddafem::schema
