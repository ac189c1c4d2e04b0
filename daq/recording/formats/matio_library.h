#pragma once

#include <cstdint>
#include <string>

#include "daq/recording/formats/library_process.h"

// The MAT-file reader's calls into matio (matio_library.cpp) for Level 4 and Level 5 files,
// compiled into oscilab_hdf5_module only: the program reaches them through the module's C
// interface (daq/hdf5_module/hdf5_module_api.h). They read untrusted files and run in a child
// process (library_process.h); they throw nothing but std::bad_alloc.
namespace oscilab::daq {

/// What a MAT-file holds (contents_to_text's text): every variable's header, no values; or the
/// problem.
ChildReply describe_mat_file(const std::string& path);

/// The `sample_count` values of one column of variable `name` (`columns` columns as described)
/// converted to double: a row when samples run along the matrix's columns.
ChildReply read_mat_values(const std::string& path, const std::string& name,
                           std::int64_t sample_count, std::int64_t columns, int column);

}  // namespace oscilab::daq
