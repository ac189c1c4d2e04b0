// Finding and loading Oscilab's modules: see module_loader.h. The directories compiled in come
// from analysis/CMakeLists.txt: OSCILAB_MODULE_RELATIVE_DIR (lib/oscilab relative to bin/),
// OSCILAB_MODULE_INSTALL_DIR and OSCILAB_MODULE_BUILD_DIR (absolute).
#include "analysis/common/module_loader.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <mutex>

#include "analysis/common/input_error.h"

namespace oscilab {
namespace {

namespace fs = std::filesystem;

// The directory of the binary this function was linked into (an executable, or the Python
// extension that embeds the core), symbolic links resolved.
fs::path own_directory() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&own_directory), &info) == 0 || info.dli_fname == nullptr) {
    return {};
  }
  std::error_code error;
  const fs::path binary = fs::canonical(info.dli_fname, error);
  return error ? fs::path(info.dli_fname).parent_path() : binary.parent_path();
}

struct Loaded {
  void* handle = nullptr;
  std::string path;
};

std::string joined(const std::vector<std::string>& directories) {
  std::string text;
  for (const std::string& directory : directories) {
    text += (text.empty() ? "" : ", ") + directory;
  }
  return text;
}

}  // namespace

std::vector<std::string> module_directories() {
  const char* override_dir = std::getenv(kModuleDirVariable);
  if (override_dir != nullptr && *override_dir != '\0') return {override_dir};
  std::vector<std::string> directories;
  const auto add = [&](const fs::path& directory) {
    const std::string text = directory.lexically_normal().string();
    for (const std::string& known : directories) {
      if (known == text) return;
    }
    directories.push_back(text);
  };
  const fs::path own = own_directory();
  if (!own.empty()) add(own / OSCILAB_MODULE_RELATIVE_DIR);
  add(OSCILAB_MODULE_INSTALL_DIR);
  add(OSCILAB_MODULE_BUILD_DIR);
  return directories;
}

void* module_entry(const std::string& file, const std::string& entry, const std::string& purpose) {
  static std::mutex mutex;
  static std::map<std::string, Loaded> loaded;  // by file name; loaded modules stay loaded
  const std::lock_guard lock(mutex);
  Loaded module;
  if (const auto known = loaded.find(file); known != loaded.end()) {
    module = known->second;
  } else {
    const std::vector<std::string> directories = module_directories();
    fs::path found;
    for (const std::string& directory : directories) {
      std::error_code error;
      if (fs::is_regular_file(fs::path(directory) / file, error)) {
        found = fs::path(directory) / file;
        break;
      }
    }
    if (found.empty()) {
      const char* override_dir = std::getenv(kModuleDirVariable);
      const bool overridden = override_dir != nullptr && *override_dir != '\0';
      throw InputError(purpose + " needs " + file + ": not found in " + joined(directories) +
                       (overridden ? std::string(" (") + kModuleDirVariable + ")"
                                   : std::string(" (is the installation complete?)")));
    }
    // RTLD_NOW: every symbol of the module and its libraries is bound here, in the parent, so
    // that a forked child never enters the dynamic loader. RTLD_NODELETE: the module stays until
    // the process exits (its libraries keep global state).
    module = {dlopen(found.c_str(), RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE), found.string()};
    if (module.handle == nullptr) {
      const char* why = dlerror();
      throw InputError(purpose + " needs " + file + ": cannot load " + found.string() + ": " +
                       (why != nullptr ? why : "unknown reason"));
    }
    loaded.emplace(file, module);
  }
  void* symbol = dlsym(module.handle, entry.c_str());
  if (symbol == nullptr) {
    throw InputError(purpose + " needs " + file + ": " + module.path + " has no entry point " +
                     entry + " (a module of another Oscilab version?)");
  }
  return symbol;
}

}  // namespace oscilab
