#pragma once

// The C interface of oscilab_hdf5_module.so, the module that holds every call into libhdf5 and
// matio: the HDF5 and MAT-file readers' work (run in a child process, library_process.h) and the
// MAT-file writer. Oscilab loads it on first use (hdf5_module_loader.h), so that a process that
// reads no HDF5 or MAT-file does not map libhdf5, matio and the 40 libraries they pull in.
//
// Only plain data crosses: C strings, numbers, arrays the caller owns, and replies in memory from
// malloc. No C++ exception leaves the module (each entry catches everything), and no C++ object
// crosses, so the module and the program may differ in their copies of the core's helpers.
// Changing a type or a function here means a new version of the entry point.
#include <stddef.h>
#include <stdint.h>

extern "C" {

/// What a reading function replies: `ok` with its payload, or a one-line problem
/// (e.g. "dataset /x: not numeric"). `bytes` comes from malloc (null when `size` is 0 or when
/// memory ran out, with ok 0); the caller frees it with free().
struct OscilabModuleReplyV1 {
  int ok;
  char* bytes;
  size_t size;
};

/// Text as UTF-8 bytes, not necessarily null-terminated.
struct OscilabTextV1 {
  const char* utf8;
  size_t size;
};

/// What a MAT-file variable holds; every variable is a column of `rows` values, except Text.
enum OscilabMatKindV1 {
  kOscilabMatDoubles = 0,   // rows×1 double (`doubles`); a scalar is 1×1
  kOscilabMatLogicals = 1,  // rows×1 logical (`logicals`, each 0 or 1)
  kOscilabMatText = 2,      // 1×k char: `texts[0]`, stored as UTF-16 code units like MATLAB's
  kOscilabMatTexts = 3,     // rows×1 cell of char: `texts[0 .. rows)`
};

/// One variable to write; the arrays stay the caller's and must outlive the call.
struct OscilabMatVariableV1 {
  const char* name;
  int kind;  // OscilabMatKindV1
  size_t rows;
  const double* doubles;
  const uint8_t* logicals;
  const OscilabTextV1* texts;
};

/// How writing a MAT-file ended.
enum OscilabMatWriteStatusV1 {
  kOscilabMatWritten = 0,
  kOscilabMatCannotCreate = 1,         // the file cannot be created; `error_number` is errno
  kOscilabMatCannotMakeVariable = 2,   // matio cannot build variable `variable`
  kOscilabMatCannotWriteVariable = 3,  // writing variable `variable` failed
  kOscilabMatCannotClose = 4,          // closing (flushing) the file failed
  kOscilabMatUnexpected = 5,           // anything else (memory ran out)
};

struct OscilabMatWriteResultV1 {
  int status;  // OscilabMatWriteStatusV1
  size_t variable;
  int error_number;
};

/// The module's functions. Those that read run in a child process only (library_process.h):
/// they may crash on a malformed file.
struct OscilabHdf5ModuleV1 {
  /// Initialises libhdf5 in the calling process (H5open): called once, in the parent.
  void (*initialise_hdf5)(void);
  /// An HDF5 file's (mat73 1: a MAT v7.3 file's) contents as contents_to_text's JSON text.
  OscilabModuleReplyV1 (*describe_hdf5)(const char* path, int mat73);
  /// `sample_count` values of dataset (MAT v7.3: variable) `name`, column `column` of a matrix,
  /// as native doubles.
  OscilabModuleReplyV1 (*read_hdf5)(const char* path, const char* name, int64_t sample_count,
                                    int column, int mat73);
  /// A MAT-file's (Level 4 or 5, through matio) contents as contents_to_text's JSON text.
  OscilabModuleReplyV1 (*describe_mat)(const char* path);
  /// `sample_count` values of variable `name` (`columns` columns), column `column`, as doubles.
  OscilabModuleReplyV1 (*read_mat)(const char* path, const char* name, int64_t sample_count,
                                   int64_t columns, int column);
  /// Writes `count` variables to a new MATLAB v5 MAT-file at `path`, zlib-compressed.
  OscilabMatWriteResultV1 (*write_mat)(const char* path, const OscilabMatVariableV1* variables,
                                       size_t count);
};

/// The entry point: `const OscilabHdf5ModuleV1* oscilab_hdf5_module_v1(void)`.
typedef const OscilabHdf5ModuleV1* (*OscilabHdf5ModuleEntryV1)(void);
}

namespace oscilab::daq {
inline constexpr const char* kHdf5ModuleFile = "oscilab_hdf5_module.so";
inline constexpr const char* kHdf5ModuleEntry = "oscilab_hdf5_module_v1";
}  // namespace oscilab::daq
