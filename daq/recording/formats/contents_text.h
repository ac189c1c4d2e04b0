#pragma once

#include <string>

#include "daq/recording/format_reader.h"

// What a reading child process (library_process.h) replies when it describes a file: its
// FileContents as JSON text, which is how the description crosses from oscilab_hdf5_module's
// code in the child to the reader in the parent.
namespace oscilab::daq {

/// FileContents as JSON text for the child's reply; invalid UTF-8 in names and attributes is
/// replaced, never thrown.
std::string contents_to_text(const FileContents& contents);
/// And back: throws InputError naming `path` when the text is not what contents_to_text writes.
FileContents contents_from_text(const std::string& text, const std::string& path);

}  // namespace oscilab::daq
