// A child process per library call: see library_process.h.
//
// Why a child process. libhdf5 1.10 and matio trust the structures a file declares; on a
// malformed file they can read out of bounds, abort (libhdf5 asserts), loop, or allocate what a
// size field says. None of that can be caught in-process. Oscilab therefore never calls either
// library in its own process: every call runs in a child made by fork(), which replies over a
// pipe; the parent turns a crash, an abnormal exit or a timeout into an InputError.
//
// Why fork() is sound here although the CLI and the GUI read recordings on several threads.
// After fork() in a multi-threaded process only the forking thread exists in the child; any lock
// another thread held at that moment stays locked forever, so POSIX allows only
// async-signal-safe functions until exec. The child here breaks that rule only where it cannot
// be avoided, and each exception is safe for a reason:
//   - The libraries' state is consistent and unlocked: the parent loads them (dlopen of
//     oscilab_hdf5_module, daq/hdf5_module/hdf5_module_loader.h) and calls H5open once, both under
//     a lock before its first child, and makes no other libhdf5 call; it calls matio only to
//     write MAT-files (mat_export.h), whose state is the file being written, not globals a child
//     reads. So no parent thread can hold a libhdf5 lock or leave its globals half-updated at the
//     moment of fork. Every reading call is made in a child, and the child loads nothing: every
//     symbol of the module was bound when it was loaded (RTLD_NOW).
//   - malloc/free: the libraries allocate. glibc's fork() takes every malloc arena lock before it
//     forks and re-initialises them in the child, and likewise the stdio list lock and the
//     dynamic loader's load lock, so the child's malloc, fopen (matio) and open/pread (libhdf5)
//     work. (This is glibc's behaviour, which Oscilab relies on; POSIX does not promise it.)
//   - Anything else a parent thread may hold (a C++ static being initialised, a mutex of our
//     own): the child's work touches only its own objects and the library, and the parent's
//     timeout kills a child that deadlocks anyway, so the worst case is an InputError, never a
//     hang of Oscilab.
//   - The child ends with _exit(): no atexit handlers, no flush of stdio buffers it inherited,
//     no destructors of the parent's statics, no library clean-up.
// Everything the child needs (the path, the limits) is prepared before fork(). The pipe is made
// with O_CLOEXEC so that a program another thread starts never inherits it.
#include "daq/recording/formats/library_process.h"

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "analysis/common/input_error.h"
#include "daq/recording/message_text.h"

#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(memory_sanitizer) || \
    __has_feature(thread_sanitizer)
#define OSCILAB_SANITIZED 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define OSCILAB_SANITIZED 1
#endif

namespace oscilab::daq {
namespace {

constexpr std::size_t kHeaderBytes = 1 + sizeof(std::uint64_t);  // status, payload length
constexpr std::size_t kMaxProblemBytes = 4096;                   // a problem is one line

// Writes everything or gives up (the parent then sees a short reply). write() is
// async-signal-safe.
bool write_all(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t written = ::write(fd, data, size);
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) return false;
    data += written;
    size -= static_cast<std::size_t>(written);
  }
  return true;
}

[[noreturn]] void child_main(int fd, const ChildLimits& limits, std::size_t parent_vm_bytes,
                             const std::function<ChildReply()>& work) {
  // A signal handler the parent installed (a crash reporter) must not run in the child: a crash
  // here is the library's, and the parent reports it.
  for (const int signal_number : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGPIPE}) {
    ::signal(signal_number, SIG_DFL);
  }
#ifndef OSCILAB_SANITIZED
  // The sanitizers reserve terabytes of shadow memory, so the address-space limit is left out
  // under them; the parent's timeout and reply limit still apply.
  if (limits.memory_bytes > 0) {
    const rlim_t limit = static_cast<rlim_t>(parent_vm_bytes + limits.memory_bytes);
    const rlimit address_space{limit, limit};
    ::setrlimit(RLIMIT_AS, &address_space);
  }
#else
  (void)limits;
  (void)parent_vm_bytes;
#endif
  ChildReply reply;
  try {
    reply = work();
  } catch (...) {
    reply = {false, "unexpected error while reading"};
  }
  if (!reply.ok && reply.bytes.size() > kMaxProblemBytes) reply.bytes.resize(kMaxProblemBytes);
  char header[kHeaderBytes];
  header[0] = reply.ok ? 'O' : 'E';
  const std::uint64_t length = reply.bytes.size();
  std::memcpy(header + 1, &length, sizeof length);
  const bool written =
      write_all(fd, header, sizeof header) && write_all(fd, reply.bytes.data(), reply.bytes.size());
  ::_exit(written ? 0 : 3);
}

std::string signal_name(int signal_number) {
  switch (signal_number) {
    case SIGSEGV:
      return "SIGSEGV, a memory access violation";
    case SIGBUS:
      return "SIGBUS, a bus error";
    case SIGABRT:
      return "SIGABRT, an abort";
    case SIGFPE:
      return "SIGFPE, an arithmetic error";
    case SIGILL:
      return "SIGILL, an illegal instruction";
    case SIGKILL:
      return "SIGKILL";
    default:
      return "signal " + std::to_string(signal_number);
  }
}

std::size_t own_address_space_bytes() {
  std::ifstream statm("/proc/self/statm");
  std::size_t pages = 0;
  statm >> pages;
  return pages * static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
}

class Pipe {
 public:
  Pipe() {
    if (::pipe2(fds_, O_CLOEXEC) != 0) fds_[0] = fds_[1] = -1;
  }
  Pipe(const Pipe&) = delete;
  Pipe& operator=(const Pipe&) = delete;
  ~Pipe() {
    close_read();
    close_write();
  }
  bool valid() const { return fds_[0] >= 0; }
  int read_end() const { return fds_[0]; }
  int write_end() const { return fds_[1]; }
  void close_read() { close_end(0); }
  void close_write() { close_end(1); }

 private:
  void close_end(int i) {
    if (fds_[i] >= 0) ::close(fds_[i]);
    fds_[i] = -1;
  }
  int fds_[2] = {-1, -1};
};

}  // namespace

std::string run_in_child(const std::string& path, const std::string& library,
                         const ChildLimits& limits, const std::function<ChildReply()>& work) {
  const std::string failed = path + ": " + library + " failed on this file (";
  Pipe pipe;
  if (!pipe.valid()) {
    throw InputError(path + ": cannot start the process that reads it with " + library + ": " +
                     std::strerror(errno));
  }
  const std::size_t parent_vm_bytes = own_address_space_bytes();
  const pid_t pid = ::fork();
  if (pid < 0) {
    throw InputError(path + ": cannot start the process that reads it with " + library + ": " +
                     std::strerror(errno));
  }
  if (pid == 0) {
    ::close(pipe.read_end());
    child_main(pipe.write_end(), limits, parent_vm_bytes, work);
  }
  pipe.close_write();

  // Read the reply while the child writes it (a pipe holds only 64 KiB), within the timeout.
  const auto deadline = std::chrono::steady_clock::now() + limits.timeout;
  std::string received;
  std::string problem;  // why the reply is unusable, when it is
  bool timed_out = false;
  std::uint64_t payload_bytes = 0;
  bool header_seen = false;
  char chunk[65536];
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      timed_out = true;
      break;
    }
    pollfd poll_fd{pipe.read_end(), POLLIN, 0};
    const int ready =
        ::poll(&poll_fd, 1, static_cast<int>(std::min<long long>(left.count(), 1000)));
    if (ready < 0 && errno != EINTR) {
      problem = std::string("waiting for it failed: ") + std::strerror(errno);
      break;
    }
    if (ready <= 0) continue;
    const ssize_t count = ::read(pipe.read_end(), chunk, sizeof chunk);
    if (count < 0 && errno == EINTR) continue;
    if (count <= 0) break;  // end of the reply (or a child that died)
    received.append(chunk, static_cast<std::size_t>(count));
    if (!header_seen && received.size() >= kHeaderBytes) {
      header_seen = true;
      std::memcpy(&payload_bytes, received.data() + 1, sizeof payload_bytes);
      const std::size_t allowed = received[0] == 'O' ? limits.max_reply_bytes : kMaxProblemBytes;
      if (payload_bytes > allowed) {
        problem = "it replied " + std::to_string(payload_bytes) + " bytes, more than the " +
                  std::to_string(allowed) + " the file can justify";
        break;
      }
      received.reserve(kHeaderBytes + static_cast<std::size_t>(payload_bytes));
    }
    if (header_seen && received.size() > kHeaderBytes + payload_bytes) {
      problem = "it replied more than it announced";
      break;
    }
  }
  if (timed_out || !problem.empty()) ::kill(pid, SIGKILL);
  pipe.close_read();
  int status = 0;
  pid_t waited = 0;
  do {
    waited = ::waitpid(pid, &status, 0);
  } while (waited < 0 && errno == EINTR);

  if (timed_out) {
    throw InputError(failed + "it did not finish within " +
                     number_text(static_cast<double>(limits.timeout.count()) / 1000.0) +
                     " s and was stopped)");
  }
  if (!problem.empty()) throw InputError(failed + problem + ")");
  if (waited == pid && WIFSIGNALED(status)) {
    throw InputError(failed + "the reading process ended with " + signal_name(WTERMSIG(status)) +
                     ")");
  }
  if (waited == pid && WIFEXITED(status) && WEXITSTATUS(status) != 0) {
    throw InputError(failed + "the reading process exited with status " +
                     std::to_string(WEXITSTATUS(status)) + ")");
  }
  if (!header_seen || received.size() != kHeaderBytes + payload_bytes) {
    throw InputError(failed + "the reading process ended without a complete reply)");
  }
  if (received[0] != 'O') {
    std::string problem = received.substr(kHeaderBytes);
    std::replace(problem.begin(), problem.end(), '\n', ' ');  // one line, whatever the library said
    std::replace(problem.begin(), problem.end(), '\r', ' ');
    throw InputError(path + ": " + problem);
  }
  received.erase(0, kHeaderBytes);
  return received;
}

ChildLimits child_limits_for(const std::string& path, std::size_t max_reply_bytes) {
  std::error_code error;
  const auto file_bytes = std::filesystem::file_size(path, error);
  const std::size_t size = error ? 0 : static_cast<std::size_t>(file_bytes);
  ChildLimits limits;
  limits.max_reply_bytes = max_reply_bytes;
  // 5 s, and 1 s more per MB: libhdf5 and matio read well over 100 MB/s, so only a library
  // that loops (libhdf5 does on some malformed files) or a machine stalled for seconds reaches it.
  limits.timeout = std::chrono::milliseconds(5000 + size / 1000);
  // 512 MiB for the library (libhdf5's chunk cache is 1 MiB per dataset), plus the reply twice
  // (the library's buffer and the child's copy) and the file once (a compressed element).
  limits.memory_bytes = (std::size_t{512} << 20) + 2 * max_reply_bytes + size;
  return limits;
}

}  // namespace oscilab::daq
