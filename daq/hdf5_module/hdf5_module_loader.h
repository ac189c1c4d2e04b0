#pragma once

#include <string>

#include "daq/hdf5_module/hdf5_module_api.h"
#include "daq/recording/formats/library_process.h"

// The program's side of oscilab_hdf5_module (hdf5_module_api.h): the HDF5 and MAT-file readers
// and the MAT-file writer get its functions here, and the module is loaded on the first call.
namespace oscilab::daq {

/// The module's functions, loaded on first use (module_entry) with libhdf5 initialised in this
/// process (H5open) before the first caller goes on: call it in the parent before forking a child
/// that uses them, and the child inherits a loaded, consistent, unlocked library. Thread-safe.
/// Throws InputError starting with `purpose` ("reading run1.h5") when the module cannot be
/// loaded, naming the module and where it was looked for.
const OscilabHdf5ModuleV1& hdf5_module(const std::string& purpose);

/// A reading function's reply as a child's reply; frees the module's buffer.
ChildReply child_reply(OscilabModuleReplyV1 reply);

}  // namespace oscilab::daq
