// Checkpoints of the far field: its Newmark state, energies, counters, springs' forces and
// snapshots, and the free-field column's own. The factorizations are not stored: the next step
// makes the one its dt needs from the same matrix (a direct solve gives the same bits whether
// its factors were kept or made anew; the iterative solver starts from the stored state).
#include "common/checkpoint_archive.h"
#include "fem/elastic_wave_model_impl.h"

#include <vector>

namespace ddafem::fem
{
namespace
{
/// deal.II's vectors as their values (the length goes with them).
template <class Archive>
void transfer_vector(Archive& a, dealii::Vector<double>& v)
{
  std::vector<double> values(v.begin(), v.end());
  transfer_all(a, values);
  if constexpr (Archive::is_loading::value)
  {
    v.reinit(values.size());
    std::copy(values.begin(), values.end(), v.begin());
  }
}

template <class Archive>
void transfer_energies(Archive& a, EnergyBalance& e)
{
  transfer_all(a, e.kinetic, e.strain, e.work_of_input, e.work_of_dashpots, e.initial,
               e.dissipated);
  transfer_all(a, e.work_of_rayleigh, e.work_of_springs);
}

template <class Archive>
void transfer_timings(Archive& a, Timings& t)
{
  transfer_all(a, t.setup, t.assemble, t.solve, t.update, t.n_steps, t.linear_iterations);
  transfer_all(a, t.n_factorizations);
}
} // namespace

template <class Archive>
void ElasticWaveModel::Impl::transfer_state(Archive& ar)
{
  transfer_marker(ar, "fem::ElasticWaveModel");
  for (Vector<double>* x : {&u, &v, &a, &static_displacement, &static_force, &a_previous, &force})
    transfer_vector(ar, *x);
  transfer_all(ar, t, initial_acceleration_done, snapshots, spring_force);
  transfer_energies(ar, energies);
  transfer_timings(ar, timings);
  bool has_column = column != nullptr;
  transfer_all(ar, has_column);
  if (has_column != (column != nullptr))
    throw std::runtime_error("checkpoint: a far field saved with another free-field boundary");
  if (column)
    column->impl->transfer_state(ar);
}

void ElasticWaveModel::save(CheckpointOut& archive) const
{
  // One function stores and restores (Boost.Serialization's `&`); storing changes nothing.
  impl->transfer_state(archive);
}

void ElasticWaveModel::load(CheckpointIn& archive)
{
  impl->transfer_state(archive);
}

} // namespace ddafem::fem
