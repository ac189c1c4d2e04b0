#pragma once

#include <string>
#include <vector>

#include "analysis/common/input_error.h"
#include "analysis/design/adaptive_test.h"
#include "daq/drive/jack_drive_client.h"

namespace oscilab::daq {

/// A run the drive ended by an abort: the message is "drive: " and the abort in words
/// (drive_abort_text); the event says which limit and what crossed it.
class DriveAborted : public InputError {
 public:
  DriveAborted(const std::string& message, const DriveEvent& event)
      : InputError(message), event_(event) {}
  const DriveEvent& event() const { return event_; }

 private:
  DriveEvent event_;
};

/// A shaker behind a JACK drive as an adaptive test's level runner: each run is a stepped sine
/// driven by the sine controller (JackDriveClient) in real time. After a lead-in at rest, each
/// level is ramped to, brought on target and held for `hold_s`; its steady window in the
/// recording runs from the cycle that came on target to the end of the hold. The inputs the drive
/// saw are resampled to the analysis rate (InterleavedResampler: every channel through the same
/// filter, sample k at t = k / rate exactly) and written to `folder` as `NN_<purpose>_<well>.wav`
/// with its sidecar (base_acc in m/s², y in m, the mass, the levels), then handed back as the
/// file reads, as the virtual rig's runner does. The shaker time of a run is its wall-clock time.
///
/// A real rig cannot move the mass from one well to the other: a run asked for the other well
/// than `positive_well` throws InputError. So do an abort (its reason and value), a level that
/// does not come on target within `settle_timeout_s` after its ramp (the drive is ramped down
/// first), a capture that lost frames, and a JACK server that shut down.
class JackLevelRunner : public analysis::LevelRunner {
 public:
  struct Options {
    JackDriveClient::Options drive;  // capture_s is set by the runner
    double mass_kg = 0.0;
    bool positive_well = true;
    double analysis_rate_hz = 512.0;
    double hold_s = 10.0;
    double lead_in_s = 2.5;
    double settle_timeout_s = 30.0;
    std::string folder;  // must exist
  };

  /// Starts the drive (throws InputError with start()'s reason).
  explicit JackLevelRunner(Options options);

  analysis::LevelRun run(const std::vector<double>& levels_n, double freq_hz, bool positive_well,
                         const std::string& purpose) override;

  /// The recordings written, in order.
  const std::vector<std::string>& paths() const { return paths_; }
  /// Every drive event of every run, in order (for an event log).
  const std::vector<DriveEvent>& events() const { return events_; }
  double server_rate_hz() const { return drive_.rate_hz(); }

 private:
  struct Capture;
  Options options_;
  JackDriveClient drive_;
  std::vector<std::string> paths_;
  std::vector<DriveEvent> events_;
};

}  // namespace oscilab::daq
