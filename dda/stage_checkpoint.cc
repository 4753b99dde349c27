// Checkpoints of a stage in progress: the time stepper's dt and counters, the settle detector's
// clocks or the release detector's windows, the stage's result so far.
#include "common/checkpoint_archive.h"
#include "dda/checkpoint_types.h"
#include "dda/dynamic_stage.h"
#include "dda/static_stage.h"
#include "dda/time_stepper.h"

namespace ddafem::dda
{
namespace
{
template <class Archive>
void transfer_result(Archive& a, DynamicStageResult& r)
{
  transfer_all(a, r.failure, r.n_steps, r.n_cuts, r.n_cut_steps, r.n_penalty_raises,
               r.n_flips_ignored);
  transfer_all(a, r.n_reversals, r.cuts_by_cause, r.smallest_dt, r.end_time, r.settled, r.moving);
  transfer_all(a, r.fallen, r.removed, r.moving_speed, r.stopped);
}

template <class Archive>
void transfer_result(Archive& a, StaticStageResult& r)
{
  transfer_all(a, r.outcome, r.n_steps, r.ratio, r.block, r.failure, r.n_cuts, r.n_cut_steps);
  transfer_all(a, r.n_penalty_raises, r.cuts_by_cause, r.smallest_dt, r.stopped);
  transfer_each(a, r.released,
                [&a](ReleasedBlock& b)
                { transfer_all(a, b.block, b.step, b.mass, b.centroid, b.ratio); });
}
} // namespace

void ReleaseDetector::save(CheckpointOut& a) const
{
  a << last_centroids;
  for (const Watch& w : watches)
    a << w.n_steps << w.start_force << w.travel << w.path;
}

void ReleaseDetector::load(CheckpointIn& a)
{
  a >> last_centroids;
  for (Watch& w : watches)
    a >> w.n_steps >> w.start_force >> w.travel >> w.path;
}

void StaticStageRun::save(CheckpointOut& a) const
{
  transfer_marker(a, "dda::StaticStageRun");
  transfer_result(a, const_cast<StaticStageResult&>(result));
  stepper.save(a);
  detector.save(a);
}

void StaticStageRun::load(CheckpointIn& a)
{
  transfer_marker(a, "dda::StaticStageRun");
  transfer_result(a, result);
  stepper.load(a);
  detector.load(a);
}

void TimeStepper::save(CheckpointOut& a) const
{
  a << dt << accepted_dt << cut_causes << cut_step_count << last_cuts << penalty_raise_count;
  a << reversal_count << resume_dt << level_successes << broken_pair << pair_broken;
}

void TimeStepper::load(CheckpointIn& a)
{
  a >> dt >> accepted_dt >> cut_causes >> cut_step_count >> last_cuts >> penalty_raise_count;
  a >> reversal_count >> resume_dt >> level_successes >> broken_pair >> pair_broken;
}

void SettleDetector::save(CheckpointOut& a) const
{
  a << quiet << has_fallen << moving_speed;
}

void SettleDetector::load(CheckpointIn& a)
{
  a >> quiet >> has_fallen >> moving_speed;
}

void DynamicStageRun::save(CheckpointOut& a) const
{
  transfer_marker(a, "dda::DynamicStageRun");
  transfer_result(a, const_cast<DynamicStageResult&>(result));
  a << first_step;
  stepper.save(a);
  const bool settling = detector.has_value();
  a << settling;
  if (settling)
    detector->save(a);
}

void DynamicStageRun::load(CheckpointIn& a)
{
  transfer_marker(a, "dda::DynamicStageRun");
  transfer_result(a, result);
  a >> first_step;
  stepper.load(a);
  bool settling = false;
  a >> settling;
  if (settling != detector.has_value())
    throw std::runtime_error("checkpoint: a settle stage saved for another kind of stage");
  if (settling)
    detector->load(a);
}

} // namespace ddafem::dda
