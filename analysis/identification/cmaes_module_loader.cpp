// cmaes_search: loads the CMA-ES module (liboscilab_cmaes.so, cmaes_search.cpp) on first use and
// calls it. The module lives in OSCILAB_CMAES_MODULE_DIR relative to the directory of the binary
// that holds this code (an executable, or a library that embeds the analysis core), which is
// where the build tree and the installation both put it.
#include <dlfcn.h>

#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <string>

#include "analysis/identification/cmaes_search.h"

namespace oscilab::analysis {
namespace {

using Entry = void (*)(int, const UnitCost*, const CmaesOptions*, const SearchProgressFn*,
                       const CancelToken*, SearchResult*);

constexpr const char* kModuleFile = "liboscilab_cmaes.so";
constexpr const char* kEntryName = "oscilab_cmaes_search_v1";

// The directory of the binary this function was linked into.
std::filesystem::path own_directory() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&own_directory), &info) == 0 || info.dli_fname == nullptr) {
    return {};
  }
  std::error_code error;
  const std::filesystem::path binary = std::filesystem::canonical(info.dli_fname, error);
  return error ? std::filesystem::path(info.dli_fname).parent_path() : binary.parent_path();
}

Entry load_entry() {
  const std::filesystem::path module = own_directory() / OSCILAB_CMAES_MODULE_DIR / kModuleFile;
  // RTLD_NODELETE: the module (and pagmo's thread pools) stay until the process exits.
  void* handle = dlopen(module.c_str(), RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
  if (handle == nullptr) {
    const char* why = dlerror();
    throw std::runtime_error(std::string("CMA-ES: cannot load the optimiser module: ") +
                             (why != nullptr ? why : module.string()) +
                             " (is the installation complete?)");
  }
  void* symbol = dlsym(handle, kEntryName);
  if (symbol == nullptr) {
    throw std::runtime_error("CMA-ES: " + module.string() + " has no " + kEntryName +
                             " (a module of another Oscilab version?)");
  }
  return reinterpret_cast<Entry>(symbol);
}

}  // namespace

SearchResult cmaes_search(int dimension, const UnitCost& cost, const CmaesOptions& options,
                          const SearchProgressFn& progress, const CancelToken& cancel) {
  static std::mutex mutex;
  static Entry entry = nullptr;
  {
    const std::lock_guard lock(mutex);
    if (entry == nullptr) entry = load_entry();  // a failed load is tried again on the next call
  }
  SearchResult result;
  entry(dimension, &cost, &options, &progress, &cancel, &result);
  return result;
}

}  // namespace oscilab::analysis
