#pragma once

#include <string>
#include <vector>

#include "daq/recording/format_reader.h"

// MAT v7.3 files through the HDF5 reader's code (hdf5_format.cpp): Debian's matio 1.5.23 crashes
// on v7.3 files (a segmentation fault in Mat_VarRead even on files it wrote itself), so the MAT
// reader reads them with libhdf5 directly, following MATLAB's layout.
namespace oscilab::daq {

/// The variables of a MAT v7.3 file: numeric datasets at the root with a "MATLAB_class"
/// attribute, with MATLAB's rows x columns (HDF5 stores them transposed). Throws InputError.
FileContents describe_mat73(const std::string& path);
/// One column of a variable describe_mat73 listed (samples along its longer dimension, along the
/// rows when square). Throws InputError.
std::vector<double> read_mat73_signal(const std::string& path, const FileSignal& signal,
                                      int column);

}  // namespace oscilab::daq
