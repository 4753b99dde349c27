// Constitutive law of a DDA contact point: penalty springs and Mohr-Coulomb with cohesion and
// tensile strength (Shi 1988, ch. 4). Pure functions, no geometry.
#pragma once

namespace ddafem::dda
{
/// State of a contact, as decided by the open-close iteration.
enum class ContactState
{
  open,  ///< no contact force: the vertex is off the edge (or the contact failed in tension)
  slide, ///< closed, the shear force is the Mohr-Coulomb limit (friction opposes the slip)
  lock   ///< closed, normal and shear springs (p and p_s) act
};

/// How a sticking contact's dashpot enters the decision to slide (evaluate_contact).
enum class DashpotDemand
{
  total,       ///< the spring's and the dashpot's shear together against the limit
  never_pushes ///< that, or the spring's alone within it: the dashpot may hold, never push
};

/// Properties of one contact point.
struct ContactLaw
{
  double normal_stiffness = 0.0; ///< p [N/m]
  double shear_stiffness = 0.0;  ///< p_s [N/m]
  double tan_friction = 0.0;     ///< tan(phi) [-]
  double cohesive_force = 0.0;   ///< cohesion x the joint length the contact carries [N]
  double tensile_capacity = 0.0; ///< tensile strength x that length [N]
};

/// A contact's state and forces. Sign conventions: `normal_force` is compression positive;
/// `shear_force` S acts on the vertex block as -S t and on the edge block as +S t, with t the
/// edge's unit tangent (anticlockwise around the edge block), so S > 0 when the vertex has moved
/// along +t relative to the edge.
struct ContactForces
{
  ContactState state = ContactState::open;
  double normal_force = 0.0; ///< N [N]
  double shear_force = 0.0;  ///< S [N]
  /// Cohesion and tensile strength still act: the contact has never slid nor failed in tension.
  bool intact = true;
};

/// The state and forces of a contact at the end of a step (one open-close trial), from its
/// state at the start of the step (`start`), its normal gap at the end of the step `gap` [m]
/// (negative: penetration) and the tangential relative displacement of the step `slip` [m]
/// (vertex relative to the edge, along t).
/// - A contact that was open closes when gap < 0. A closed contact opens when the normal spring
///   pulls (gap > 0), unless it is intact and the pull p gap stays within its tensile capacity.
///   Failing in tension ends its cohesion and tensile strength.
/// - A closed contact locks when the elastic trial S0 + p_s slip is within the Mohr-Coulomb
///   limit N tan(phi) + c (c only while intact), and slides otherwise with S = +-limit in the
///   direction of the trial; sliding ends cohesion and tensile strength.
/// - `viscous_shear` [N], same sign convention as S: the shear force of a sticking contact's
///   dashpot at the step's end (dda/damping.h). The dashpot sits beside the shear spring, the
///   two in series with the slider (a Kelvin-Voigt element and a Coulomb slider): the demand
///   the limit must hold is the spring's and the dashpot's shear together
///   (DashpotDemand::total); the strength is the springs' alone (N is the normal spring's force)
///   and the stored S the spring's. DashpotDemand::never_pushes also lets a contact stick whose
///   spring alone is within the limit: the open-close iteration's fallback for a contact at the
///   limit that would flip on the dashpot's last newton (System::update_trial_state).
ContactForces evaluate_contact(const ContactLaw& law, const ContactForces& start, double gap,
                               double slip, double viscous_shear = 0.0,
                               DashpotDemand demand = DashpotDemand::total);

/// Whether forces beyond the law's strength act on an intact bond (a bonded joint's end spring):
/// a pull beyond the tensile capacity, -normal_force > tensile_capacity, or a shear beyond
/// Mohr-Coulomb, |shear_force| > max(0, cohesive_force + normal_force tan(phi)) (a pull lowers
/// the shear strength). `normal_force` [N] is compression positive, `shear_force` [N] of either
/// sign. Unlike evaluate_contact's limit for a contact, the friction term is not cut off at zero
/// normal force: a bond's shear strength falls with tension.
bool exceeds_strength(const ContactLaw& law, double normal_force, double shear_force);

/// The trial an open-close iteration (from 1) takes from the law's `next`, given the previous
/// trial. From the second iteration on, a contact whose sliding direction reverses between two
/// trials is taken as locked: the elastic trial S0 + p_s slip stays within the limit only in a
/// band 2 N tan(phi) / p_s wide (0.1 um for 5 kN on a 1e11 N/m joint), which the slip of a
/// sliding trial on either side jumps over, so the iteration would flip between the two
/// directions for ever (a block whose slip stops and turns within the step). The next
/// iteration solves with the shear spring and the law then decides lock or slide from where
/// the slip ends. In the first iteration the previous trial is the start state, and a
/// reversal is the step's own. (System applies it only with slip reversals localised.)
ContactForces iteration_trial(unsigned iteration, const ContactForces& previous,
                              const ContactForces& next);

/// Whether two trials differ in what the next iteration assembles: the state, or the direction
/// of sliding.
bool state_changed(const ContactForces& a, const ContactForces& b);

/// Whether a contact's change of trial state from `before` to `after` in open-close iteration
/// `iteration` (from 1) keeps the iteration going. Every change counts in the first two
/// iterations; from the third on, a contact that carries at most `negligible` [N] (its larger
/// of |normal force| and |shear force|) before and after is let go: flipping between slide and
/// lock under a kN where the rock carries MN changes nothing the blocks feel.
bool change_holds_iteration(unsigned iteration, const ContactForces& before,
                            const ContactForces& after, double negligible);

} // namespace ddafem::dda
