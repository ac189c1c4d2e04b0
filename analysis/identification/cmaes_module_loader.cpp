// cmaes_search: loads the CMA-ES module (liboscilab_cmaes.so, cmaes_search.cpp) on first use, as
// every Oscilab module is loaded (analysis/common/module_loader.h), and calls it.
#include <string>

#include "analysis/common/module_loader.h"
#include "analysis/identification/cmaes_search.h"

namespace oscilab::analysis {
namespace {

using Entry = void (*)(int, const UnitCost*, const CmaesOptions*, const SearchProgressFn*,
                       const CancelToken*, SearchResult*);

constexpr const char* kModuleFile = "liboscilab_cmaes.so";
constexpr const char* kEntryName = "oscilab_cmaes_search_v1";

}  // namespace

SearchResult cmaes_search(int dimension, const UnitCost& cost, const CmaesOptions& options,
                          const SearchProgressFn& progress, const CancelToken& cancel) {
  // A failed load throws InputError naming the module and the directories, and is tried again
  // on the next call.
  const auto entry =
      reinterpret_cast<Entry>(module_entry(kModuleFile, kEntryName, "a CMA-ES search"));
  SearchResult result;
  entry(dimension, &cost, &options, &progress, &cancel, &result);
  return result;
}

}  // namespace oscilab::analysis
