#pragma once

#include <cstddef>

#include "daq/hdf5_module/hdf5_module_api.h"

// The MAT-file writer's calls into matio (mat_file_writer.cpp), compiled into oscilab_hdf5_module
// only: mat_export.h reaches it through the module's C interface. It throws nothing but
// std::bad_alloc.
namespace oscilab::daq {

/// Writes `count` variables, in order, to a new MATLAB v5 MAT-file at `path` with zlib-compressed
/// elements (which MATLAB ≥ 7, Octave and scipy.io.loadmat read). Char arrays are stored as
/// UTF-16 code units, as MATLAB stores them; a byte of the UTF-8 text that does not start a
/// valid sequence becomes U+FFFD. On failure the file may be left half-written: the caller
/// writes to a temporary (TemporaryFile).
OscilabMatWriteResultV1 write_mat_file(const char* path, const OscilabMatVariableV1* variables,
                                       std::size_t count);

}  // namespace oscilab::daq
