// ContactLaw: the open-close decision and Mohr-Coulomb forces of one contact point against hand
// calculations.
//
// Every expected force is one or two products of exactly representable numbers (p = 1e9 N/m,
// gaps and slips of 1e-6 to 1e-3 m), so rounding stays below 1e-15 relative; the tolerance 1e-9 N
// is far below the smallest force that distinguishes two outcomes (1 N).
#include "dda/contact/contact_law.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace ddafem::dda;

namespace
{
constexpr double tol = 1e-9; // [N]

/// p = 1e9 N/m, p_s = 4e8 N/m, tan(phi) = 0.5, cohesive force 300 N, tensile capacity 200 N.
ContactLaw law()
{
  ContactLaw l;
  l.normal_stiffness = 1e9;
  l.shear_stiffness = 4e8;
  l.tan_friction = 0.5;
  l.cohesive_force = 300.0;
  l.tensile_capacity = 200.0;
  return l;
}

ContactForces closed(double normal, double shear, bool intact = true)
{
  ContactForces f;
  f.state = ContactState::lock;
  f.normal_force = normal;
  f.shear_force = shear;
  f.intact = intact;
  return f;
}
} // namespace

TEST(ContactLaw, OpenContactStaysOpenWithAPositiveGap)
{
  const ContactForces out = evaluate_contact(law(), ContactForces{}, 1e-6, 1e-3);
  EXPECT_EQ(out.state, ContactState::open);
  EXPECT_EQ(out.normal_force, 0.0);
  EXPECT_EQ(out.shear_force, 0.0);
  // An open contact that never closed keeps its cohesion: it has not failed.
  EXPECT_TRUE(out.intact);
}

TEST(ContactLaw, OpenContactClosesWhenItPenetrates)
{
  // N = -p gap = 1e9 x 1e-6 = 1000 N; a new contact has no previous shear: S = p_s slip =
  // 4e8 x 1e-6 = 400 N, within N tan(phi) + c = 500 + 300 = 800 N: lock.
  const ContactForces out = evaluate_contact(law(), ContactForces{}, -1e-6, 1e-6);
  EXPECT_EQ(out.state, ContactState::lock);
  EXPECT_NEAR(out.normal_force, 1000.0, tol);
  EXPECT_NEAR(out.shear_force, 400.0, tol);
  EXPECT_TRUE(out.intact);
}

TEST(ContactLaw, LockedContactAddsTheShearSpringToItsPreviousShear)
{
  // S = S0 + p_s slip = 100 - 4e8 x 1e-6 = -300 N, within 800 N.
  const ContactForces out = evaluate_contact(law(), closed(1000.0, 100.0), -1e-6, -1e-6);
  EXPECT_EQ(out.state, ContactState::lock);
  EXPECT_NEAR(out.shear_force, -300.0, tol);
}

TEST(ContactLaw, SlidesAtTheFrictionLimitWithTheSignOfTheSlip)
{
  // Trial S = 4e8 x 3e-6 = 1200 N > 800 N: slide; cohesion is lost, S = N tan(phi) = 500 N in
  // the direction of the slip, and -500 N for the opposite slip.
  for (const double sign : {1.0, -1.0})
  {
    SCOPED_TRACE(sign);
    const ContactForces out = evaluate_contact(law(), closed(1000.0, 0.0), -1e-6, sign * 3e-6);
    EXPECT_EQ(out.state, ContactState::slide);
    EXPECT_NEAR(out.normal_force, 1000.0, tol);
    EXPECT_NEAR(out.shear_force, sign * 500.0, tol);
    EXPECT_FALSE(out.intact);
  }
}

TEST(ContactLaw, CohesionHoldsUntilTheLimitAndIsLostAfterSliding)
{
  // Trial 4e8 x 1.9e-6 = 760 N: within 800 N with cohesion (lock, intact), beyond 500 N once the
  // contact has slid (not intact): it slides at 500 N.
  const ContactForces held = evaluate_contact(law(), closed(1000.0, 0.0), -1e-6, 1.9e-6);
  EXPECT_EQ(held.state, ContactState::lock);
  EXPECT_NEAR(held.shear_force, 760.0, tol);
  EXPECT_TRUE(held.intact);
  const ContactForces after_slip =
      evaluate_contact(law(), closed(1000.0, 0.0, false), -1e-6, 1.9e-6);
  EXPECT_EQ(after_slip.state, ContactState::slide);
  EXPECT_NEAR(after_slip.shear_force, 500.0, tol);
  EXPECT_FALSE(after_slip.intact);
  // Just beyond 800 N: the same contact slides even though it was intact.
  const ContactForces beyond = evaluate_contact(law(), closed(1000.0, 0.0), -1e-6, 2.1e-6);
  EXPECT_EQ(beyond.state, ContactState::slide);
  EXPECT_NEAR(beyond.shear_force, 500.0, tol);
}

TEST(ContactLaw, FrictionlessSlidingContactCarriesNoShear)
{
  ContactLaw smooth = law();
  smooth.tan_friction = 0.0;
  smooth.cohesive_force = 0.0;
  const ContactForces out = evaluate_contact(smooth, closed(1000.0, 0.0, false), -1e-6, -1e-3);
  EXPECT_EQ(out.state, ContactState::slide);
  EXPECT_EQ(out.shear_force, 0.0);
}

TEST(ContactLaw, TensileCapacityHoldsThenFails)
{
  // A closed intact contact pulled by p gap = 1e9 x 1.5e-7 = 150 N <= 200 N holds (N = -150 N);
  // the friction limit is then only the cohesion, 300 N.
  const ContactForces held = evaluate_contact(law(), closed(1000.0, 0.0), 1.5e-7, 5e-7);
  EXPECT_EQ(held.state, ContactState::lock);
  EXPECT_NEAR(held.normal_force, -150.0, tol);
  EXPECT_NEAR(held.shear_force, 200.0, tol);
  EXPECT_TRUE(held.intact);
  // 250 N > 200 N: it opens and loses its strength for good.
  const ContactForces failed = evaluate_contact(law(), closed(1000.0, 0.0), 2.5e-7, 0.0);
  EXPECT_EQ(failed.state, ContactState::open);
  EXPECT_EQ(failed.normal_force, 0.0);
  EXPECT_FALSE(failed.intact);
  // Closing again, it has no tensile capacity left: the smallest pull opens it.
  const ContactForces pulled = evaluate_contact(law(), closed(1000.0, 0.0, false), 1e-9, 0.0);
  EXPECT_EQ(pulled.state, ContactState::open);
  // An open contact never resists a pull, even if intact.
  const ContactForces never = evaluate_contact(law(), ContactForces{}, 1e-9, 0.0);
  EXPECT_EQ(never.state, ContactState::open);
  EXPECT_TRUE(never.intact);
}

TEST(ContactLaw, ClosedContactWithoutTensileStrengthOpensAndLosesCohesion)
{
  ContactLaw no_tension = law();
  no_tension.tensile_capacity = 0.0;
  const ContactForces out = evaluate_contact(no_tension, closed(1000.0, 0.0), 1e-9, 0.0);
  EXPECT_EQ(out.state, ContactState::open);
  EXPECT_FALSE(out.intact);
}

TEST(ContactLaw, StateChangedComparesStateAndSlidingDirection)
{
  ContactForces slide_plus = closed(1000.0, 500.0);
  slide_plus.state = ContactState::slide;
  ContactForces slide_minus = slide_plus;
  slide_minus.shear_force = -500.0;
  ContactForces slide_other_magnitude = slide_plus;
  slide_other_magnitude.shear_force = 300.0;
  const ContactForces lock_a = closed(1000.0, 100.0), lock_b = closed(2000.0, -100.0);
  EXPECT_FALSE(state_changed(lock_a, lock_b)); // same state, forces differ
  EXPECT_TRUE(state_changed(lock_a, slide_plus));
  EXPECT_TRUE(state_changed(ContactForces{}, lock_a));
  EXPECT_TRUE(state_changed(slide_plus, slide_minus)); // the friction force flips
  EXPECT_FALSE(state_changed(slide_plus, slide_other_magnitude));
  // Frictionless sliding has no direction to flip.
  ContactForces smooth = slide_plus;
  smooth.shear_force = 0.0;
  EXPECT_FALSE(state_changed(smooth, slide_minus));
}

// From the third open-close iteration on, a contact flipping between slide and lock while
// carrying at most the negligible force (flip_force_ratio x the step's largest normal force)
// before and after no longer holds the iteration back; one that carries more always does.
TEST(ContactLaw, FlipsAtAlmostNoForceAreLetGoFromTheThirdIteration)
{
  const double negligible = 1e3; // N: 1e-3 of a 1 MN contact elsewhere
  ContactForces lock_small = closed(800.0, 200.0), slide_small = closed(800.0, -300.0);
  slide_small.state = ContactState::slide;
  EXPECT_TRUE(change_holds_iteration(1, lock_small, slide_small, negligible));
  EXPECT_TRUE(change_holds_iteration(2, lock_small, slide_small, negligible));
  EXPECT_FALSE(change_holds_iteration(3, lock_small, slide_small, negligible));
  EXPECT_FALSE(change_holds_iteration(6, slide_small, lock_small, negligible));
  // Carrying more than the negligible force before or after (normal or shear): it counts.
  EXPECT_TRUE(change_holds_iteration(3, lock_small, closed(1500.0, 0.0), negligible));
  EXPECT_TRUE(change_holds_iteration(3, closed(500.0, -1200.0), slide_small, negligible));
  // Opening from nothing to nothing: let go.
  EXPECT_FALSE(change_holds_iteration(4, ContactForces{}, lock_small, negligible));
}

// A sliding direction that reverses between two trials of the open-close iteration is taken as
// lock (the slip that keeps the elastic trial within the limit lies between the two sliding
// solutions); in the first iteration the previous trial is the step's start and a reversal
// stands. Everything else passes through unchanged.
TEST(ContactLaw, SlidingThatReversesBetweenTrialsIsTakenAsLock)
{
  ContactForces slide_plus = closed(1000.0, 500.0, false), slide_minus = slide_plus;
  slide_plus.state = slide_minus.state = ContactState::slide;
  slide_minus.shear_force = -500.0;

  const ContactForces locked = iteration_trial(2, slide_plus, slide_minus);
  EXPECT_EQ(locked.state, ContactState::lock);
  EXPECT_NEAR(locked.normal_force, 1000.0, tol);
  EXPECT_NEAR(locked.shear_force, 0.0, tol);
  EXPECT_FALSE(locked.intact);
  EXPECT_EQ(iteration_trial(5, slide_minus, slide_plus).state, ContactState::lock);

  // The step's own reversal (iteration 1: the previous trial is the start state).
  EXPECT_EQ(iteration_trial(1, slide_plus, slide_minus).state, ContactState::slide);
  EXPECT_NEAR(iteration_trial(1, slide_plus, slide_minus).shear_force, -500.0, tol);
  // Same direction, lock to slide, slide to lock: the law's trial as it is.
  EXPECT_EQ(iteration_trial(3, slide_plus, slide_plus).state, ContactState::slide);
  EXPECT_EQ(iteration_trial(3, closed(1000.0, 100.0), slide_minus).state, ContactState::slide);
  EXPECT_EQ(iteration_trial(3, slide_plus, closed(1000.0, -100.0)).state, ContactState::lock);
  // Frictionless sliding has no direction to reverse.
  ContactForces smooth = slide_plus;
  smooth.shear_force = 0.0;
  EXPECT_EQ(iteration_trial(3, smooth, slide_minus).state, ContactState::slide);
}

// A bond's strength (law(): cohesive force 300 N, tensile capacity 200 N, tan(phi) 0.5):
// tension beyond 200 N, or |S| beyond 300 + 0.5 N, exceeds it; at the limits it holds.
TEST(ContactLaw, BondExceedsItsStrengthJustBeyondTheLimits)
{
  const double above_200 = std::nextafter(200.0, 1e9), below_200 = std::nextafter(200.0, 0.0);
  EXPECT_FALSE(exceeds_strength(law(), -200.0, 0.0));
  EXPECT_FALSE(exceeds_strength(law(), -below_200, 0.0));
  EXPECT_TRUE(exceeds_strength(law(), -above_200, 0.0));

  // N = 1000 N compression: 300 + 500 = 800 N either way.
  const double above_800 = std::nextafter(800.0, 1e9), below_800 = std::nextafter(800.0, 0.0);
  EXPECT_FALSE(exceeds_strength(law(), 1000.0, 800.0));
  EXPECT_FALSE(exceeds_strength(law(), 1000.0, -800.0));
  EXPECT_FALSE(exceeds_strength(law(), 1000.0, below_800));
  EXPECT_TRUE(exceeds_strength(law(), 1000.0, above_800));
  EXPECT_TRUE(exceeds_strength(law(), 1000.0, -above_800));

  // A pull lowers the shear strength: N = -100 N leaves 300 - 50 = 250 N.
  EXPECT_FALSE(exceeds_strength(law(), -100.0, 250.0));
  EXPECT_TRUE(exceeds_strength(law(), -100.0, std::nextafter(250.0, 1e9)));
}

// Without cohesion a pull leaves no shear strength (not a negative one): any shear breaks it.
TEST(ContactLaw, BondShearStrengthIsNeverNegative)
{
  ContactLaw l = law();
  l.cohesive_force = 0.0;
  EXPECT_FALSE(exceeds_strength(l, -100.0, 0.0));
  EXPECT_TRUE(exceeds_strength(l, -100.0, 1e-9));
  EXPECT_TRUE(exceeds_strength(l, -100.0, -1e-9));
}

TEST(ContactLaw, DashpotIsInTheShearDemandOfAStickingContact)
{
  // A contact that has slid (no cohesion): N = 1000 N (gap -1e-6 m), limit 500 N. Its dashpot's
  // shear at the step's end (dda/damping.h) is beside the spring, the two in series with the
  // slider.
  const ContactForces start = closed(1000.0, 0.0, false);
  // The spring within the limit (400 N at slip 1e-6 m), the dashpot 50 N more: 450 N sticks,
  // and the stored force is the spring's.
  const ContactForces held = evaluate_contact(law(), start, -1e-6, 1e-6, 50.0);
  EXPECT_EQ(held.state, ContactState::lock);
  EXPECT_NEAR(held.shear_force, 400.0, tol);
  // The dashpot 200 N more: 600 N slides at the limit...
  const ContactForces pushed = evaluate_contact(law(), start, -1e-6, 1e-6, 200.0);
  EXPECT_EQ(pushed.state, ContactState::slide);
  EXPECT_NEAR(pushed.shear_force, 500.0, tol);
  // ...unless the dashpot may only hold (the open-close iteration's fallback): the spring alone
  // is within the limit.
  EXPECT_EQ(evaluate_contact(law(), start, -1e-6, 1e-6, 200.0, DashpotDemand::never_pushes).state,
            ContactState::lock);
  // The spring beyond the limit (600 N at 1.5e-6 m), the dashpot -200 N (it resists the slip
  // that unloads the spring): together 400 N hold it, in either demand.
  for (const DashpotDemand demand : {DashpotDemand::total, DashpotDemand::never_pushes})
  {
    const ContactForces relieved = evaluate_contact(law(), start, -1e-6, 1.5e-6, -200.0, demand);
    EXPECT_EQ(relieved.state, ContactState::lock);
    EXPECT_NEAR(relieved.shear_force, 600.0, tol);
  }
  // Both beyond (600 N and 700 N): slides at the limit, in the direction of the demand; and
  // without a dashpot the 600 N spring slides.
  const ContactForces slides =
      evaluate_contact(law(), start, -1e-6, 1.5e-6, 100.0, DashpotDemand::never_pushes);
  EXPECT_EQ(slides.state, ContactState::slide);
  EXPECT_NEAR(slides.shear_force, 500.0, tol);
  EXPECT_EQ(evaluate_contact(law(), start, -1e-6, 1.5e-6).state, ContactState::slide);
}
