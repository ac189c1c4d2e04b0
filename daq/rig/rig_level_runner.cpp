#include "daq/rig/rig_level_runner.h"

#include <cstdio>
#include <utility>

#include "analysis/common/input_error.h"
#include "daq/recording/measurement_mapping.h"
#include "daq/recording/recording.h"
#include "daq/rig/virtual_rig.h"

namespace oscilab::daq {

RigLevelRunner::RigLevelRunner(analysis::Model truth, std::string folder, Schedule schedule,
                               std::uint64_t seed)
    : truth_(std::move(truth)), folder_(std::move(folder)), schedule_(schedule), seed_(seed) {}

analysis::LevelRun RigLevelRunner::run(const std::vector<double>& levels_n, double freq_hz,
                                       bool positive_well, const std::string& purpose) {
  analysis::SteppedSineSchedule schedule;
  schedule.frequency_hz = freq_hz;
  schedule.levels_n = levels_n;
  schedule.hold_s = schedule_.hold_s;
  schedule.ramp_s = schedule_.ramp_s;
  schedule.lead_in_s = schedule_.lead_in_s;
  RigSpec spec;
  spec.positive_well = positive_well;
  spec.seed = seed_ * 1000 + static_cast<std::uint64_t>(paths_.size());
  const RigRecording rig = record_stepped_sine(truth_, schedule, spec);
  if (rig.status != analysis::TimeSimulator::Status::Ok) {
    throw InputError("virtual rig: " + rig.message);
  }
  char name[96];
  std::snprintf(name, sizeof name, "%02zu_%s_%s.wav", paths_.size(), purpose.c_str(),
                positive_well ? "positive" : "negative");
  const std::string path = folder_ + "/" + name;
  write_recording(rig.recording, path);
  paths_.push_back(path);
  analysis::LevelRun out;
  out.channels = measurement_channels(rig.recording);
  out.channels.name = name;
  out.shaker_s = schedule.duration_s();
  return out;
}

}  // namespace oscilab::daq
