#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <string>

#include "daq/recording/format_reader.h"

// Runs a C library's reading of one file (libhdf5, matio) in a child process, so that a crash,
// an abort, a hang or a runaway allocation of the library on a malformed file becomes an
// InputError naming the file instead of ending or freezing Oscilab.
namespace oscilab::daq {

/// What the child sends back: `ok` with its payload, or the one-line problem it found.
struct ChildReply {
  bool ok = false;
  std::string bytes;  // ok: the payload; else the problem, e.g. "dataset /x: not numeric"
};

/// Limits of one child. The parent never holds more than `max_reply_bytes` of the reply.
struct ChildLimits {
  std::size_t max_reply_bytes = 0;
  std::chrono::milliseconds timeout{60000};
  std::size_t memory_bytes = 0;  // address space the child may add to the parent's; 0: no limit
};

/// Runs `work` in a forked child process and returns its payload. `work` runs only in the child:
/// it may call the library and allocate, but must not take locks that other threads of the
/// parent may hold (see library_process.cpp), and it must not throw. Throws InputError
/// "path: problem" when the child replies a problem, and "path: <library> failed on this file
/// (...)" when the child crashes, aborts, exceeds a limit or does not finish in time.
std::string run_in_child(const std::string& path, const std::string& library,
                         const ChildLimits& limits, const std::function<ChildReply()>& work);

/// Limits for reading `path` with a reply of at most `max_reply_bytes`: a timeout that grows with
/// the file's size and memory for the library proportional to the file and the reply.
ChildLimits child_limits_for(const std::string& path, std::size_t max_reply_bytes);

/// The maximum ratio of deflate (zlib) output to input, 1032:1: a bound on how many bytes a
/// compressed element of a file can hold per byte of the file.
inline constexpr std::size_t kMaxDeflateRatio = 1032;

}  // namespace oscilab::daq
