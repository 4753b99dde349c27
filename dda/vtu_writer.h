// VTU/PVD time series of the blocks for ParaView: one VTK_POLYGON cell per block.
// deal.II's DataOut writes patches of quadrilaterals only; DDA blocks are arbitrary polygons, so
// this small writer emits VTK XML UnstructuredGrid files directly.
#pragma once

#include "common/checkpoint_fwd.h"
#include "dda/bolt_snapshot.h"
#include "dda/snapshot.h"

#include <string>
#include <utility>
#include <vector>

namespace ddafem::dda
{
/// Writes DIR/BASENAME_NNNNN.vtu per call and rewrites DIR/BASENAME.pvd after each one (so the
/// series opens in ParaView even if the run stops early). Cell data: block_id (Int64),
/// material (Int32), displacement, velocity (3-component Float64, z = 0), stress (Float64 with
/// components sxx, syy, sxy) and von_mises [Pa]. Point coordinates are the current vertices.
/// I/O failures throw std::runtime_error naming the file.
class VtuSeriesWriter
{
public:
  VtuSeriesWriter(std::string directory, std::string basename);

  /// Writes one snapshot at simulated time `time` [s]; returns the .vtu path written.
  std::string write(double time, const std::vector<BlockSnapshot>& blocks);
  /// Writes one snapshot of contact points (a series holds either blocks or contacts): one
  /// VTK_VERTEX cell per point with cell data id, block_a, block_b, state (Int32: 0 open,
  /// 1 slide, 2 lock, 3 bonded joint end), normal (3-component), normal_force [N, compression
  /// positive], shear_force [N], gap [m, negative: penetration] and slip [m].
  std::string write(double time, const std::vector<ContactSnapshot>& contacts);
  /// Writes one snapshot of bolts: one VTK_POLY_LINE cell per bolt (BoltSnapshot's points),
  /// cell data bolt_id, type (Int32: 0 end_anchored, 1 grouted), axial_force [N, tension
  /// positive; grouted: the largest of its crossings], shear_force [N, grouted: the largest
  /// |dowel force|] and state (Int32: 0 elastic, 1 yielding, 2 slack, 3 ruptured); point data
  /// point_axial_force and point_shear_force [N] (a grouted bolt's crossings' own; 0 at its
  /// ends).
  std::string write(double time, const std::vector<BoltSnapshot>& bolts);

  /// Writes one snapshot whose .vtu text is `text` (dda/vtu_text.h): an element kind's own
  /// series, written by its outputs (app/run/<element>_outputs.cc).
  std::string write_text(double time, const std::string& text);

  std::size_t n_written() const { return entries.size(); }

  /// Checkpoints: the files written so far. `load` rewrites the .pvd with them (a resumed run:
  /// later files of the interrupted run drop out of the series and are written again).
  void save(CheckpointOut& archive) const;
  void load(CheckpointIn& archive);

private:
  void write_pvd() const;
  std::string directory;
  std::string basename;
  std::vector<std::pair<double, std::string>> entries; ///< (time, file name relative to dir)
};

} // namespace ddafem::dda
