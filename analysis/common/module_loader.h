#pragma once

#include <string>
#include <vector>

// Oscilab's own shared modules (lib/oscilab/*.so): code bound to a large C library (libhdf5 and
// matio, cairo) that a process loads with dlopen only when a run needs it, so that a command that
// never touches those formats does not pay for mapping and relocating their libraries at start.
namespace oscilab {

/// The environment variable that, when set and not empty, is the only directory searched for
/// modules (a test, or a relocated installation).
inline constexpr const char* kModuleDirVariable = "OSCILAB_MODULE_DIR";

/// The directories searched for a module, in order: $OSCILAB_MODULE_DIR alone when it is set;
/// else lib/oscilab relative to the directory of the binary that holds this code (an executable
/// in bin/, or the Python extension, whose package mirrors that layout), then the installation's
/// lib/oscilab and the build tree's, as configured.
std::vector<std::string> module_directories();

/// The address of `entry` in module `file` (e.g. "oscilab_hdf5_module.so"), which the first call
/// loads from the first of module_directories() that holds it; later calls reuse it (a failed
/// load is tried again). Call it before forking: the child must not load anything. Thread-safe.
///
/// Throws InputError, whose message starts with `purpose` (e.g. "reading run1.mat"), when the
/// module is in none of the directories ("reading run1.mat needs oscilab_hdf5_module.so: not found
/// in /usr/lib/oscilab, ..."), when it cannot be loaded (the loader's reason), or when it lacks
/// `entry` (a module of another Oscilab version).
void* module_entry(const std::string& file, const std::string& entry, const std::string& purpose);

}  // namespace oscilab
