// The element kinds of the blocks' model and their order in the step (dda/element.h).
#include "dda/bolt.h"
#include "dda/grouted_bolt.h"
#include "dda/lining.h"

namespace ddafem::dda
{
std::vector<std::unique_ptr<ElementKind>> make_element_kinds(const ModelDescription& model,
                                                             const ElementHost& host)
{
  std::vector<std::unique_ptr<ElementKind>> kinds;
  kinds.push_back(std::make_unique<Bolts>(model, host));
  kinds.push_back(std::make_unique<Linings>(model, host));
  kinds.push_back(std::make_unique<GroutedBolts>(model));
  return kinds;
}

} // namespace ddafem::dda
