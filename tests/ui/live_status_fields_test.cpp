// The status strip's texts and severities.
#include "ui/live_status_fields.h"

#include <map>
#include <string>

#include <gtest/gtest.h>

namespace oscilab::ui {
namespace {

TEST(StatusFields, ShowEveryFigureOfTheIssueWithItsSeverity) {
  daq::AcquisitionStatus s;
  s.source = "virtual rig";
  s.running = true;
  s.sample_rate_hz = 512;
  s.stream_time_s = 12.25;
  s.samples = 6272;
  s.queue_fill = 200;
  s.queue_capacity = 256;
  s.recording = true;
  s.recorded_samples = 1024;
  s.cycles = 90;
  s.excluded_cycles = 2;
  s.edc_latency_s = 0.031;
  FaultCounts faults;
  faults.gaps = 1;
  faults.gap_samples = 32;
  FaultTracker tracker;
  tracker.update(faults, 1.0);
  const auto fields = status_fields(s, faults, tracker, 1.0, 5120.0);
  std::map<std::string, StatusField> by_key;
  for (const auto& f : fields) by_key[f.key] = f;
  for (const char* key :
       {"source", "rate", "time", "samples", "gaps", "duplicates", "reordered", "nan", "saturated",
        "overflow", "queue", "recording", "cycles", "levels", "latency", "alarms", "errors"}) {
    EXPECT_EQ(by_key.count(key), 1u) << key;
  }
  EXPECT_EQ(by_key["rate"].value, "512 Hz \u00d710");
  EXPECT_EQ(by_key["time"].value, "12.2 s");  // %.1f rounds half to even on 12.25
  EXPECT_EQ(by_key["samples"].value, "6272");
  EXPECT_EQ(by_key["gaps"].value, "32 (1)");
  EXPECT_EQ(by_key["gaps"].severity, Severity::Fault);
  EXPECT_EQ(by_key["duplicates"].severity, Severity::Normal);
  EXPECT_EQ(by_key["queue"].value, "200/256");
  EXPECT_EQ(by_key["queue"].severity, Severity::Warning);  // over 3/4 full
  EXPECT_EQ(by_key["recording"].value, "\u25cf 2.0 s");    // 1024 samples at 512 Hz
  EXPECT_EQ(by_key["cycles"].value, "90 (2 excl.)");
  EXPECT_EQ(by_key["latency"].value, "31 ms");
}

}  // namespace
}  // namespace oscilab::ui
