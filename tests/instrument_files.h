#pragma once

#include <string>

#include <gtest/gtest.h>

namespace oscilab::testing {

/// The folder of real instruments' files (NI TDMS, UFF 58 exports, a MATLAB file written at
/// acquisition, a DAS interrogator's HDF5) that the readers' tests read in place. They are not
/// part of this repository: their folder is the build setting OSCILAB_INSTRUMENT_FILES (from the
/// environment variable of the same name at configure time); empty when none was given.
inline std::string instrument_files() { return OSCILAB_INSTRUMENT_FILES; }

}  // namespace oscilab::testing

/// Skips a test that reads real instruments' files when the build was not told where they are
/// (a checkout without them); with a folder given, a missing file fails the test by its path.
#define OSCILAB_SKIP_WITHOUT_INSTRUMENT_FILES()                                                   \
  if (oscilab::testing::instrument_files().empty())                                               \
  GTEST_SKIP() << "no folder of real instruments' files: configure with OSCILAB_INSTRUMENT_FILES" \
                  " set to it"
