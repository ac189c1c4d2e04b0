// A recording opened to be looked at (opened_recording.h): its min/max overview against the
// extremes taken sample by sample, the second method; windows of a sound container read by
// seeking against the rows read_recording gives, AC-coupled channels included; and a bad sample
// that the opening pass meets refused in the reader's words.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "daq/recording/opened_recording.h"
#include "tests/daq/recording/recording_test_util.h"

namespace oscilab::daq {
namespace {

using testing::TempDir;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The extremes of samples [first, end) of a column, NaN left out (NaN when all are).
std::pair<double, double> extremes(const Eigen::MatrixXd& x, Eigen::Index c, Eigen::Index first,
                                   Eigen::Index end) {
  double lo = kNaN, hi = kNaN;
  for (Eigen::Index i = first; i < end; ++i) {
    lo = std::fmin(lo, x(i, c));
    hi = std::fmax(hi, x(i, c));
  }
  return {lo, hi};
}

bool same(double a, double b) { return (std::isnan(a) && std::isnan(b)) || a == b; }

TEST(SampleOverview, EveryBucketOfEveryLevelHoldsItsSamplesExtremes) {
  // 3 channels of 100 003 samples (a last partial bucket), a stretch of NaN as an invalid
  // interval leaves, long enough to make whole level-0 buckets NaN.
  std::mt19937 random(7);
  std::normal_distribution<double> noise;
  Eigen::MatrixXd x(100003, 3);
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    for (Eigen::Index c = 0; c < 3; ++c) x(i, c) = (c + 1) * noise(random);
  }
  x.block(5000, 1, 300, 1).setConstant(kNaN);
  SampleOverview overview(3);
  for (Eigen::Index first = 0; first < x.rows(); first += 777) {  // blocks across buckets
    overview.add(x.middleRows(first, std::min<Eigen::Index>(777, x.rows() - first)));
  }
  overview.finish();
  EXPECT_EQ(overview.sample_count(), x.rows());
  // 1563 level-0 buckets: 11 halvings to one.
  EXPECT_EQ(overview.level_count(), 12);
  for (const Eigen::Index max_buckets :
       {Eigen::Index{1}, Eigen::Index{7}, Eigen::Index{100}, Eigen::Index{5000}}) {
    for (const auto& [first, end] : std::vector<std::pair<Eigen::Index, Eigen::Index>>{
             {0, x.rows()}, {4990, 5400}, {12345, 67890}, {99000, 200000}}) {
      for (Eigen::Index c = 0; c < 3; ++c) {
        const Eigen::Index size = overview.bucket_samples_for(first, end, max_buckets);
        const SampleOverview::Envelope e = overview.envelope(c, first, end, size);
        const Eigen::Index clipped_end = std::min(end, x.rows());
        ASSERT_FALSE(e.min.empty());
        EXPECT_EQ(e.bucket_samples, size);
        // The finest level that fits (the coarsest, one bucket, always does): twice as fine
        // would not.
        EXPECT_LE(Eigen::Index(e.min.size()), max_buckets);
        if (size > SampleOverview::kFinestBucket) {
          const Eigen::Index finer = size / 2;
          EXPECT_GT((clipped_end - 1) / finer - first / finer + 1, max_buckets);
        }
        EXPECT_LE(e.first_sample, first);
        EXPECT_GT(e.first_sample + Eigen::Index(e.min.size()) * e.bucket_samples, clipped_end - 1);
        for (std::size_t k = 0; k < e.min.size(); ++k) {
          const Eigen::Index b0 = e.first_sample + Eigen::Index(k) * e.bucket_samples;
          const auto [lo, hi] = extremes(x, c, b0, std::min(b0 + e.bucket_samples, x.rows()));
          ASSERT_TRUE(same(e.min[k], lo) && same(e.max[k], hi))
              << "channel " << c << " bucket " << k << " of " << e.bucket_samples;
        }
      }
    }
  }
  // The NaN stretch covers samples 5000..5299: of the level-0 buckets 78 (4992..5055) to 82
  // (5248..5311), the first and the last hold finite samples too, 79 to 81 nothing else.
  const SampleOverview::Envelope nan_part = overview.envelope(1, 4992, 5312, 64);
  ASSERT_EQ(nan_part.min.size(), 5u);
  EXPECT_TRUE(std::isfinite(nan_part.min[0]) && std::isfinite(nan_part.max[4]));
  for (std::size_t k = 1; k <= 3; ++k) {
    EXPECT_TRUE(std::isnan(nan_part.min[k]) && std::isnan(nan_part.max[k])) << k;
  }
  EXPECT_EQ(overview.max_abs(2), x.col(2).cwiseAbs().maxCoeff());
  EXPECT_TRUE(overview.envelope(0, 200000, 300000, 64).min.empty());  // beyond the record
}

// Base acceleration, mass displacement and a force at 512 Hz, each a sine (recording_test_util.h),
// stored at scales fine enough for a 24-bit container to keep them to 1e-6 of their amplitudes.
Recording three_channels(Eigen::Index samples) {
  return testing::sine_recording(
      512.0, samples,
      {testing::channel("base_acc", ChannelRole::Base, Quantity::Acceleration, "m/s^2", 1e-6),
       testing::channel("y", ChannelRole::Mass, Quantity::Displacement, "m", 1e-7),
       testing::channel("f", ChannelRole::Force, Quantity::Force, "N", 1e-8)});
}

TEST(OpenedRecording, WindowsOfASoundContainerAreTheRowsReadWhole) {
  const TempDir dir;
  Recording made = three_channels(40000);
  made.sidecar.channels[1].ac_coupling_hz = 0.5;  // the inverse is a recursion over the record
  for (const std::string extension : {".flac", ".w64"}) {
    const std::string path = dir.file("run" + extension);
    write_recording(made, path);
    const Recording whole = read_recording(path);
    const OpenedRecording opened = open_recording_for_review(path);
    EXPECT_EQ(opened.sample_count(), whole.sample_count());
    EXPECT_EQ(opened.container, whole.container);
    EXPECT_EQ(opened.source_path, path);
    // Out of order, across the states kept every 4096 samples, at the ends, clipped.
    for (const auto& [first, count] : std::vector<std::pair<Eigen::Index, Eigen::Index>>{
             {30000, 500}, {0, 10}, {4095, 3}, {12288, 4097}, {39990, 100}, {8191, 1}}) {
      const Eigen::MatrixXd window = opened.samples->read(first, count);
      const Eigen::Index expected = std::min(count, whole.sample_count() - first);
      ASSERT_EQ(window.rows(), expected) << path << " " << first;
      EXPECT_EQ(window, whole.samples_si.middleRows(first, expected)) << path << " " << first;
    }
    // The overview of the file is the one of the samples read whole.
    const OpenedRecording held = hold_recording(whole);
    for (Eigen::Index c = 0; c < 3; ++c) {
      const auto a = opened.overview->envelope(c, 0, whole.sample_count(), 256);
      const auto b = held.overview->envelope(c, 0, whole.sample_count(), 256);
      EXPECT_EQ(a.min, b.min);
      EXPECT_EQ(a.max, b.max);
    }
    // The analysis streams from the file; the export reads it whole again.
    EXPECT_NE(opened.samples->measurement_channels().source, nullptr);
    EXPECT_EQ(opened.samples->whole().samples_si, whole.samples_si);
  }
}

TEST(OpenedRecording, OtherFormatsAreHeldInMemory) {
  const TempDir dir;
  const Recording made = three_channels(3000);
  write_recording(made, dir.file("run.csv"));
  const OpenedRecording opened = open_recording_for_review(dir.file("run.csv"));
  const Recording whole = read_recording(dir.file("run.csv"));
  EXPECT_EQ(opened.samples->read(0, 5000), whole.samples_si);
  EXPECT_EQ(opened.samples->measurement_channels().source, nullptr);
  EXPECT_EQ(opened.overview->max_abs(0), whole.samples_si.col(0).cwiseAbs().maxCoeff());
}

TEST(OpenedRecording, ANanTheOpeningPassMeetsIsRefusedInTheReadersWords) {
  const TempDir dir;
  const Recording made = three_channels(30000);
  write_recording(made, dir.file("nan.wav"));
  std::string bytes = testing::read_file(dir.file("nan.wav"));
  const std::size_t data = bytes.find("data", 12) + 8;  // float64 samples, interleaved
  std::memcpy(&bytes[data + 8 * (3 * 20000 + 1)], &kNaN, sizeof kNaN);
  testing::write_file(dir.file("nan.wav"), bytes);
  EXPECT_EQ(testing::input_error_of([&] { open_recording_for_review(dir.file("nan.wav")); }),
            dir.file("nan.wav") + ": channel \"" + made.sidecar.channels[1].name +
                "\": sample 20000 (t = 39.0625 s) is NaN");
}

TEST(OpenedRecording, AFileShorterThanItsHeaderIsRefusedAsTruncated) {
  const TempDir dir;
  write_recording(three_channels(30000), dir.file("cut.flac"));
  const std::string bytes = testing::read_file(dir.file("cut.flac"));
  testing::write_file(dir.file("cut.flac"), bytes.substr(0, bytes.size() / 2));
  const std::string message =
      testing::input_error_of([&] { open_recording_for_review(dir.file("cut.flac")); });
  EXPECT_EQ(message.rfind(dir.file("cut.flac") + ": truncated: the header promises ", 0), 0u)
      << message;
}

TEST(OpenedRecording, AFileCutAfterItWasOpenedIsRefusedByTheReadThatMeetsIt) {
  // Another program truncates the file while the app shows it: the window read past the cut
  // throws InputError naming the file (the view keeps what it drew), nothing crashes, and what
  // the file still holds reads as before.
  const TempDir dir;
  const std::string path = dir.file("cut_later.w64");
  write_recording(three_channels(30000), path);
  const OpenedRecording opened = open_recording_for_review(path);
  const Eigen::MatrixXd head = opened.samples->read(100, 50);
  // In place (the same file, as a program that truncates it does; a file replaced by another
  // leaves the opened one readable).
  std::filesystem::resize_file(path, std::filesystem::file_size(path) / 2);
  const std::string message = testing::input_error_of([&] { opened.samples->read(25000, 100); });
  EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
  EXPECT_EQ(opened.samples->read(100, 50), head);
}

TEST(OpenedRecording, TheOpeningReportsItsProgressAndStopsWhenCancelled) {
  // 300 000 samples: five windows of 2^16 in the overview's pass, so five reports before the
  // last one, each the share of the samples gone through (0, 65536/N, ...), then 1. A CSV is
  // read whole first: its read reports the share of its bytes every 4096 lines, as the first
  // kReadShare of the opening, and the pass the rest.
  const TempDir dir;
  constexpr Eigen::Index kSamples = 300000;
  for (const std::string extension : {".w64", ".csv"}) {
    const std::string path = dir.file("long" + extension);
    write_recording(three_channels(kSamples), path);
    std::vector<double> reports;
    OpeningControl control;
    control.progress = [&](double f) { reports.push_back(f); };
    const OpenedRecording opened = open_recording_for_review(path, control);
    EXPECT_EQ(opened.sample_count(), kSamples);
    ASSERT_GE(reports.size(), 6u) << path;
    EXPECT_EQ(reports.front(), 0.0) << path;
    EXPECT_EQ(reports.back(), 1.0) << path;
    EXPECT_TRUE(std::is_sorted(reports.begin(), reports.end())) << path;
    const bool read_whole = extension == std::string(".csv");
    const double pass_start = read_whole ? kReadShare : 0.0;
    EXPECT_DOUBLE_EQ(reports[reports.size() - 2],
                     pass_start + (1.0 - pass_start) * 4.0 * 65536.0 / kSamples)
        << path;
    if (read_whole) {
      // 300 000 lines: 73 looks at the control during the read, each below kReadShare.
      const auto during_read = std::count_if(reports.begin(), reports.end(),
                                             [](double f) { return f > 0.0 && f < kReadShare; });
      EXPECT_EQ(during_read, 300001 / 4096) << path;
    }

    // Cancelled at the third window: the pass stops there and nothing is returned.
    OpeningControl cancelled;
    int windows = 0;
    cancelled.progress = [&](double f) {
      if (f > 0.0 && ++windows == 2) cancelled.cancel.cancel();
    };
    EXPECT_THROW(open_recording_for_review(path, cancelled), OpeningCancelled) << path;
    EXPECT_EQ(windows, 2) << path;
  }
}

}  // namespace
}  // namespace oscilab::daq
