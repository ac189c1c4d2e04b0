#include "daq/hdf5_module/hdf5_module_loader.h"

#include <cstdlib>
#include <mutex>

#include "analysis/common/module_loader.h"

namespace oscilab::daq {

const OscilabHdf5ModuleV1& hdf5_module(const std::string& purpose) {
  static std::mutex mutex;
  static const OscilabHdf5ModuleV1* functions = nullptr;
  const std::lock_guard lock(mutex);
  if (functions == nullptr) {  // a failed load is tried again on the next call
    const auto entry = reinterpret_cast<OscilabHdf5ModuleEntryV1>(
        module_entry(kHdf5ModuleFile, kHdf5ModuleEntry, purpose));
    const OscilabHdf5ModuleV1* loaded = entry();
    // The parent's only libhdf5 call (library_process.cpp): made under the lock, so no caller
    // forks before it has finished.
    loaded->initialise_hdf5();
    functions = loaded;
  }
  return *functions;
}

ChildReply child_reply(OscilabModuleReplyV1 reply) {
  ChildReply child;
  child.ok = reply.ok != 0;
  if (reply.bytes != nullptr) child.bytes.assign(reply.bytes, reply.size);
  std::free(reply.bytes);
  if (!child.ok && child.bytes.empty()) child.bytes = "out of memory while reading";
  return child;
}

}  // namespace oscilab::daq
