// The scene schema's settings sections (time, contacts, solver, output), each key declared once
// beside the field it fills (app/schema/bound_keys.h): the readers fill the structs by the same
// declarations.
#include "app/schema/bound_sections.h"

#include "app/schema/schema_sections.h"

namespace ddafem::schema
{
BoundKeys<dda::TimeSettings> time_keys()
{
  using S = dda::TimeSettings;
  BoundKeys<S> k;
  k.field("dt", &S::dt).unit("s").required().greater_than(0).meaning("time step");
  k.field("end_time", &S::end_time)
      .unit("s")
      .required()
      .greater_than(0)
      .meaning("simulated duration; must be >= dt");
  k.field("integrator", &S::integrator)
      .meaning("bathe (the default): Bathe's composite scheme, a generalized-alpha "
               "(rho_inf 1/2) and a three-point backward Euler half step per dt, two solves "
               "per step; right for frictional sliding and falls (within 0.71%) and for "
               "waves (the bar's record error 0.70% at 200 steps per period), "
               "docs/verification/failure.md; with a far field, the far field takes the "
               "trapezoidal rule on each half step. generalized_alpha "
               "(Chung & Hulbert 1993): one solve per step, sliding within 0.51%, but the "
               "bar's record error 1.55% at 200 steps per period; dda: Shi's first-order "
               "scheme (damps waves, but not stiff contact modes: its spectral radius "
               "returns to 1 as omega dt grows); newmark_trapezoidal: energy-conserving, "
               "second order (penalty contacts ring: blocks bounce and slide too far)");
  k.field("spectral_radius", &S::spectral_radius)
      .at_least(0)
      .at_most(1)
      .meaning("generalized_alpha: the spectral radius at infinite frequency rho_inf (1: "
               "no algorithmic damping; 0: stiff modes annihilated in one step)");
  k.field("control", &S::control)
      .meaning("adaptive: dt is the largest step, cut by cut_factor when a step fails "
               "(open-close iteration not converged, a vertex moving more than "
               "contacts.max_displacement_ratio allows, too deep a penetration) and grown "
               "back by growth_factor (blocks tied to a far field: on the levels "
               "dt / 2^k, doubling after as many steps as growth_factor takes to double; "
               "coupling/README.md); fixed: every step has dt and such a failure stops "
               "the run (wave problems)");
  k.field("dt_min", &S::dt_min)
      .unit("s")
      .default_note("dt / 10^4")
      .greater_than(0)
      .meaning("smallest step of adaptive control; a step that needs less stops the run");
  k.field("cut_factor", &S::cut_factor)
      .greater_than(0)
      .less_than(1)
      .meaning("dt multiplier after a failed step (Shi: 0.3)");
  k.field("growth_factor", &S::growth_factor)
      .at_least(1)
      .meaning("dt multiplier after an accepted step, up to dt");
  k.field("reversal_tolerance", &S::reversal_tolerance)
      .unit("m")
      .at_least(0)
      .meaning("adaptive control: the slip error a sliding contact's reversal within a "
               "step may leave (its friction acted the wrong way for part of the step: "
               "the speed error times the duration of the slide it ends); a step with a "
               "larger one is redone to end just before the reversal and dt goes back up "
               "at the next step; with generalized-alpha, a step in which friction turns "
               "around is redone from the jump and the open-close iteration locks a "
               "contact whose sliding reverses between trials (these two only on slides "
               "of at least 10 steps: shorter ones are contacts chattering under a wave). "
               "1e-6 makes two-way sliding on a shaken joint exact "
               "(docs/verification/failure.md, part 1b); 0: none (docs/design.md, "
               "Integrators)");
  return k;
}

Section time_section()
{
  return {"time", "Time stepping.", time_keys().keys()};
}

BoundKeys<dda::ContactSettings> contacts_keys()
{
  using S = dda::ContactSettings;
  BoundKeys<S> k;
  k.field("max_displacement_ratio", &S::max_displacement_ratio)
      .greater_than(0)
      .less_than(1)
      .meaning("Shi's g2: the largest vertex displacement of a step over w0 (the bound is "
               "at most a tenth of the shortest edge); a step beyond is cut");
  k.field("search_distance", &S::search_distance)
      .unit("m")
      .default_note("2.5 x the step displacement bound")
      .greater_than(0)
      .meaning("how close a vertex must come to an edge to be a contact candidate");
  k.field("max_penetration", &S::max_penetration)
      .unit("m")
      .default_note("the step displacement bound")
      .greater_than(0)
      .meaning("deepest penetration a step may leave; a step beyond is cut");
  k.field("max_open_close_iterations", &S::max_open_close_iterations)
      .at_least(1)
      .meaning("open-close iterations before the step is cut (Shi: 6)");
  k.field("max_penalty_factor", &S::max_penalty_factor)
      .at_least(1)
      .meaning("a contact penetrating deeper than max_penetration has its springs raised "
               "x 10 and the step redone (ntdda), up to this multiple of its joint "
               "material's; then dt is cut");
  k.field("flip_force_ratio", &S::flip_force_ratio)
      .at_least(0)
      .less_than(1)
      .meaning("from the third open-close iteration on, a contact whose forces stay below "
               "this fraction of the step's largest contact normal force changes state "
               "without holding the iteration back (no flipping between slide and lock "
               "at almost no force); 0 counts every change");
  k.field("angle_tolerance", &S::angle_tolerance_deg)
      .unit("deg")
      .greater_than(0)
      .less_than(30)
      .meaning("edges this close to parallel touch edge to edge; vertices this close to "
               "180 degrees are straight (never enter)");
  return k;
}

Section contacts_section()
{
  return {"contacts",
          "Contact detection and the open-close iteration (Shi 1988). w0 is half the model's size "
          "(the larger side of the blocks' bounding box, halved). The step displacement bound is "
          "g2 w0, but at most a tenth of the shortest block edge.",
          contacts_keys().keys()};
}

BoundKeys<dda::SolverSettings> solver_keys()
{
  using S = dda::SolverSettings;
  BoundKeys<S> k;
  k.field("method", &S::method)
      .meaning("direct: the sparse direct solver of `type`, its factors reused as a "
               "preconditioner while they serve; block_pcg: conjugate gradients "
               "preconditioned by the blocks' 6x6 diagonal, warm-started, no "
               "factorization (for many contacts changing state; the direct solver when "
               "it does not converge, see docs/performance/contact_bench.md)");
  k.field("type", &S::direct)
      .meaning("the sparse direct solver (block_pcg's fallback): block_ldlt: sparse "
               "Cholesky on the 6x6 blocks (fastest, see docs/performance/dda_bench.md); "
               "eigen_ldlt: Eigen SimplicialLDLT; klu: SuiteSparse KLU");
  k.field("tolerance", &S::tolerance)
      .greater_than(0)
      .less_than(1e-3)
      .meaning("block_pcg: relative residual, in the norm of the diagonal blocks' "
               "inverses, at which it stops");
  k.field("max_iterations", &S::max_iterations)
      .at_least(1)
      .meaning("block_pcg: iterations before the direct solver takes over (for this dt "
               "for the next 100 solves)");
  return k;
}

Section solver_section()
{
  return {"solver", "Linear solver for each step's system.", solver_keys().keys()};
}

BoundKeys<OutputSettings> output_keys()
{
  using S = OutputSettings;
  BoundKeys<S> k;
  k.field("directory", &S::directory)
      .meaning("output directory, relative to the working directory; `-o DIR` overrides");
  k.field("interval", &S::interval)
      .unit("s")
      .at_least(0)
      .meaning("simulated time between block snapshots; 0: first and last only");
  k.field("history_every", &S::history_every)
      .at_least(1)
      .meaning("time steps between rows of the monitor histories (a step of bathe is "
               "its pair of half steps)");
  k.field("flush_interval", &S::flush_interval)
      .unit("s")
      .at_least(0)
      .meaning("wall-clock time between flushes of histories.h5 and of the running "
               "summary.json to disk: a run killed at any moment keeps every history row "
               "up to its last flush readable; 0: after every step");
  k.field("checkpoint_every", &S::checkpoint_every)
      .unit("s")
      .at_least(0)
      .meaning("wall-clock time between checkpoints (checkpoint.bin) from which `ddafem "
               "resume DIR` continues a killed or stopped run, its histories bit for bit "
               "those of an uninterrupted run; written between two steps of a stage, "
               "and when a budget stops the run; 0: none");
  k.field("vtu_compression", &S::vtu_compression)
      .meaning("zlib level of the far field's VTU files (deal.II DataOut): best_compression "
               "writes files a few percent smaller in about four times the time "
               "(docs/performance.md, profile); the blocks' files are plain text");
  return k;
}

Section output_section()
{
  return {"output", "Where and how often results are written.", output_keys().keys()};
}

} // namespace ddafem::schema
