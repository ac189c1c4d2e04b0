#pragma once

#include <string>
#include <vector>

#include "daq/recording/format_reader.h"

// MAT v7.3 files through the HDF5 reader's code (hdf5_format.cpp): Debian's matio 1.5.23 crashes
// on v7.3 files (a segmentation fault in Mat_VarRead even on files it wrote itself), so the MAT
// reader reads them with libhdf5 directly, following MATLAB's layout.
namespace oscilab::daq {

/// Initialises libhdf5 in this process once (H5open), before the first child is forked, so that
/// each child does not pay for it (about 1.3 ms). Safe with respect to fork (library_process.cpp):
/// std::call_once finishes the initialisation before any caller goes on to fork, and the parent
/// makes no other libhdf5 call, so every child inherits a consistent, unlocked library.
void initialise_hdf5_once();

/// The variables of a MAT v7.3 file: numeric datasets at the root with a "MATLAB_class"
/// attribute, with MATLAB's rows x columns (HDF5 stores them transposed). Throws InputError.
FileContents describe_mat73(const std::string& path);
/// One column of a variable describe_mat73 listed (samples along its longer dimension, along the
/// rows when square). Throws InputError.
std::vector<double> read_mat73_signal(const std::string& path, const FileSignal& signal,
                                      int column);

}  // namespace oscilab::daq
