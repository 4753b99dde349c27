// When, within a step, a sliding contact's slip reverses: the event that step control
// localises so that friction does not act the wrong way for most of a step. Pure functions of
// one contact, no geometry.
#pragma once

#include "dda/contact/contact.h"
#include "dda/contact/contact_law.h"
#include "dda/integrator.h"

namespace ddafem::dda
{
/// A contact point's tangential motion over one step: the vertex relative to the edge, along
/// the edge's unit tangent t (positive along +t, as ContactForces::shear_force).
struct TangentialMotion
{
  double velocity = 0.0;     ///< at the step's start [m/s]
  double acceleration = 0.0; ///< at the step's start, the integrator's a_n [m/s^2]
  double slip = 0.0;         ///< over the step [m]
};

/// The relative velocity at the step's end [m/s]: Newmark's update with the integrator's beta
/// and gamma, v1 = v0 + dt ((1 - gamma) a0 + gamma a1), a1 = (slip - dt v0 - dt^2 (1/2 - beta)
/// a0) / (beta dt^2), exact for the blocks' rigid-body and strain motion at the contact point.
double end_velocity(const IntegratorCoefficients& c, double dt, const TangentialMotion& m);

/// A slip reversal within a step, as fractions of the step [-].
struct SlipReversal
{
  /// when the relative velocity, taken linear in the step from v0 to v1, crossed zero:
  /// theta = v0 / (v0 - v1); 0: no reversal
  double at = 0.0;
  /// how long the step's shear force acted the wrong way: the step applies the end state's
  /// force throughout, so friction still opposing the old direction acted wrongly after the
  /// reversal (1 - theta), friction the other way or the shear spring before it (theta)
  double mistimed = 0.0;
  /// the error in relative velocity that leaves [m/s], estimated as |v1 - v0| x mistimed: the
  /// step's change of relative velocity, friction's work, over the part acted the wrong way
  double speed_error = 0.0;
};

/// The slip error [m] a velocity error `speed_error` [m/s] left at a reversal grows to over the
/// next slide, taken as long as the slide the reversal ended, `slide_duration` [s]: a contact
/// chattering under a wave (slides of a few steps, micrometres per second) leaves nanometres,
/// a block sliding to and fro on a shaken joint (slides of tenths of a second) millimetres.
inline double slip_error(double speed_error, double slide_duration)
{
  return speed_error * slide_duration;
}

/// The reversal of a contact that slid at the step's start (`start`, relative velocity v0 along
/// its slip) and is closed at its end (`end`, relative velocity v1 against v0). Friction stops
/// the slip but does not drive it: the step's friction keeps its direction as long as the step's
/// slip does, and a stiff shear spring locked for a whole step turns the slip around instead of
/// stopping it (v1 = 2 slip / dt - v0 with DDA's scheme). No reversal when the contact did not
/// slide, opened, v0 already pointed the new way or v1 still the old one.
SlipReversal slip_reversal(const ContactForces& start, const ContactForces& end, double v0,
                           double v1);

/// Whether the slide a contact is in has lasted at least 10 steps of dt [s], so that the
/// friction restart and the open-close lock rule apply to it. Under a wave, contacts of a rock
/// mass at rest slide for a few steps at a time (15 to 120 us at dt 3e-5 s in the horseshoe)
/// with speed jumps of 0.1 m/s: restarting or locking those fed energy into it (docs/design.md,
/// Integrators); a block sliding on a shaken joint slides for 0.1 s. Shorter slides are
/// contacts chattering under a wave, not a block sliding on a joint.
inline bool slides_long_enough(const Contact& c, double dt)
{
  constexpr double min_slide_steps = 10.0; // [-]
  return c.slide_duration >= min_slide_steps * dt;
}

} // namespace ddafem::dda
