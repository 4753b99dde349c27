// Bolts' types (docs/support.md): the grouted bolts' keys and their crossings through the blocks
// at t = 0 (dda/grouted_bolt.h), for `bolts[i]` and the bolts `tunnel.bolts` generates.
#include "app/scene/scene_readers.h"

#include "app/scene/scene_text.h"
#include "common/format.h"

#include <cmath>

namespace ddafem::scene_reading
{
namespace
{
/// The keys that only a grouted bolt has.
constexpr std::array<const char*, 3> grouted_keys = {"grout_modulus", "debonded_length",
                                                     "shear_capacity"};
} // namespace

std::string find_grouted_crossings(dda::BoltDescription& b, const dda::ModelDescription& model)
{
  std::vector<std::vector<Point>> polygons;
  polygons.reserve(model.blocks.size());
  for (const dda::BlockDescription& block : model.blocks)
    polygons.push_back(block.vertices);
  const BlockBoxes boxes = block_boxes(model);
  std::array<double, 2> gap = {0.0, 0.0};
  b.crossings = dda::find_bolt_crossings(polygons, b.head, b.anchor, 1e3 * boxes.tolerance, &gap);
  const Vector2 e = (b.anchor - b.head).normalized();
  if (gap[1] > 0.0)
    return "runs through a void between " + format_point(b.head + gap[0] * e) + " and " +
           format_point(b.head + gap[1] * e) +
           " (in no block): expected a grouted bolt that lies in blocks from its head to its "
           "anchor";
  if (b.crossings.empty())
    return "does not reach a second block (its line from " + format_point(b.head) + " to " +
           format_point(b.anchor) +
           " lies in one block): expected a grouted bolt that crosses a block boundary (longer, "
           "or elsewhere)";
  return {};
}

void read_bolt_type(const MapReader& r, dda::BoltDescription& b, const dda::ModelDescription& model)
{
  if (b.type == dda::BoltType::end_anchored)
  {
    for (const char* key : grouted_keys)
      if (r.has(key))
        throw r.error(key,
                      "a key of grouted bolts: expected `type: grouted` or no " + std::string(key));
    return;
  }
  b.shear_capacity =
      r.has("shear_capacity") ? r.number("shear_capacity") : b.yield_force / std::sqrt(3.0);
  if (const std::string problem = find_grouted_crossings(b, model); !problem.empty())
    throw r.error("anchor", "the grouted bolt " + b.name + " " + problem);
}

} // namespace ddafem::scene_reading
