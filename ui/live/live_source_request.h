#pragma once

#include <optional>
#include <string>
#include <vector>

#include "daq/live/source_factory.h"
#include "daq/sources/rig_source.h"
#include "ui/live/live_settings.h"

namespace oscilab::ui {

/// What daq::make_source needs to make the source the live settings describe: its spec ("rig",
/// "file:REC", "net:127.0.0.1:PORT" or "jack:BASE,MASS") and its options. The app and the CLI
/// make their sources through the one factory (daq/live/source_factory.h).
struct LiveSourceRequest {
  std::string spec;
  daq::SourceOptions options;
};

/// The request for `settings`, the rig with `schedule` (empty: at rest until told) for
/// `duration_s` (none: until stopped). Reads the JACK calibration sidecar. Throws InputError
/// when the source lacks a field it needs (a replay without a file, JACK without a calibration)
/// or the sidecar cannot be read.
LiveSourceRequest live_source_request(const LiveSettings& settings,
                                      const std::vector<daq::ExcitationStep>& schedule,
                                      std::optional<double> duration_s);

}  // namespace oscilab::ui
