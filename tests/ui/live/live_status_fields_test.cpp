// The status strip's texts and severities.
#include "ui/live/live_status_fields.h"

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
  for (const char* key : {"source", "rate", "time", "samples", "gaps", "duplicates", "reordered",
                          "nan", "saturated", "overflow", "queue", "recording", "cycles", "levels",
                          "latency", "alarms", "errors", "card"}) {
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
  EXPECT_EQ(by_key["card"].value, "\u2014");  // not a sound card
}

// A sound card's faults: xruns, a lost server, a pulled cable and a rate change in one figure,
// red while fresh, every counter of the source in its tooltip.
TEST(StatusFields, ShowASoundCardsFaults) {
  daq::AcquisitionStatus s;
  s.source = "JACK default";
  s.running = true;
  FaultTracker tracker;
  auto card = [&](double now_s) {
    const FaultCounts faults = FaultCounts().merged(s);
    tracker.update(faults, now_s);
    for (const StatusField& f : status_fields(s, faults, tracker, now_s, 0.0)) {
      if (f.key == "card") return f;
    }
    return StatusField{};
  };
  StatusField f = card(1.0);
  EXPECT_EQ(f.value, "0");
  EXPECT_EQ(f.severity, Severity::Normal);
  s.jack.xruns = 2;
  s.jack.server_losses = 1;
  s.jack.port_disconnections = 1;
  s.jack.rate_changes = 1;
  s.jack.dropped_frames = 480;
  s.jack.clipped_samples = 7;
  s.jack.reconnections = 1;
  f = card(2.0);
  EXPECT_EQ(f.value, "5");
  EXPECT_EQ(f.severity, Severity::Fault);
  EXPECT_NE(f.tooltip.find("2 xrun(s)"), std::string::npos) << f.tooltip;
  EXPECT_NE(f.tooltip.find("480 frame(s) dropped"), std::string::npos) << f.tooltip;
  EXPECT_NE(f.tooltip.find("7 input sample(s) clipped"), std::string::npos) << f.tooltip;
  EXPECT_NE(f.tooltip.find("1 reconnection(s)"), std::string::npos) << f.tooltip;
  EXPECT_EQ(card(10.0).severity, Severity::Warning);  // no longer fresh, still non-zero
}

}  // namespace
}  // namespace oscilab::ui
