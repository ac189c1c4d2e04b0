#pragma once

#include <cstdint>
#include <string>

#include "daq/recording/formats/library_process.h"

// The HDF5 reader's calls into libhdf5 (hdf5_library.cpp), compiled into oscilab_hdf5_module only:
// the program reaches them through the module's C interface (daq/hdf5_module/hdf5_module_api.h).
// They read untrusted files and run in a child process (library_process.h); they throw nothing
// but std::bad_alloc.
namespace oscilab::daq {

/// H5open, in the parent before the first child, so that each child does not pay for it (about
/// 1.3 ms).
void initialise_hdf5();

/// What an HDF5 file holds (contents_to_text's text), or the problem. `mat73`: a MAT v7.3 file,
/// whose numeric datasets at the root with a "MATLAB_class" attribute are MATLAB's variables,
/// with MATLAB's rows x columns (HDF5 stores them transposed).
ChildReply describe_hdf5_file(const std::string& path, bool mat73);

/// The `sample_count` values of one column of dataset (MAT v7.3: variable) `name` as native
/// doubles (samples along its longer dimension, along dim 0, MATLAB's rows, when square).
ChildReply read_hdf5_values(const std::string& path, const std::string& name,
                            std::int64_t sample_count, int column, bool mat73);

}  // namespace oscilab::daq
