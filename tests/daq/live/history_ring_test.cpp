#include "daq/live/history_ring.h"

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace oscilab::daq {
namespace {

constexpr double kHistoryRateHz = 512.0;
constexpr double kNaNSample = std::numeric_limits<double>::quiet_NaN();

// Writes `n` samples from `first` in blocks of 16: base = value(s), the other traces offsets of
// it, the derived ones `lag` samples later; records the truth per sample.
struct Writer {
  HistoryRing& ring;
  std::vector<double> truth;  // base value per sample (NaN where none)
  int lag = 0;
  std::mt19937_64 rng{7};
  double value(std::uint64_t s) {
    while (truth.size() <= s) {
      std::normal_distribution<double> noise;
      // A slow sine with noise, and now and then a NaN (a hole a reader must skip).
      const double t = static_cast<double>(truth.size()) / kHistoryRateHz;
      truth.push_back(truth.size() % 997 == 5 ? kNaNSample : std::sin(0.7 * t) + 0.1 * noise(rng));
    }
    return truth[s];
  }
  void write(std::uint64_t first, std::uint64_t n) {
    std::vector<double> base(16), mass(16), force(16), derived(16);
    for (std::uint64_t start = first; start < first + n; start += 16) {
      HistoryRing::BlockWrite w;
      w.measured_first = start;
      w.measured_count = 16;
      for (int r = 0; r < 16; ++r) {
        const double v = value(start + static_cast<std::uint64_t>(r));
        base[static_cast<std::size_t>(r)] = v;
        mass[static_cast<std::size_t>(r)] = 2 * v;
        force[static_cast<std::size_t>(r)] = -v;
      }
      w.base = base.data();
      w.mass = mass.data();
      w.force_n = force.data();
      if (start + 16 > static_cast<std::uint64_t>(lag)) {
        w.derived_first = start + 16 > static_cast<std::uint64_t>(lag) + 16 ? start - lag : 0;
        w.derived_count = static_cast<int>(start + 16 - lag - w.derived_first);
        for (int r = 0; r < w.derived_count; ++r) {
          derived[static_cast<std::size_t>(r)] =
              3 * value(w.derived_first + static_cast<std::uint64_t>(r));
        }
        w.z_m = derived.data();
      }
      ring.write(w);
    }
  }
};

// The reference envelope of samples [start, stop] of the truth: min and max in the order they
// occur (each at its first occurrence), NaN when the bucket holds no number.
std::pair<double, double> envelope(const std::vector<double>& truth, std::uint64_t start,
                                   std::uint64_t stop, double scale) {
  double lo = kNaNSample, hi = kNaNSample;
  std::uint64_t lo_at = start, hi_at = start;
  for (std::uint64_t s = start; s <= stop; ++s) {
    const double v = scale * truth[s];
    if (!std::isfinite(v)) continue;
    if (!(v >= lo)) lo = v, lo_at = s;
    if (!(v <= hi)) hi = v, hi_at = s;
  }
  return lo_at <= hi_at ? std::pair{lo, hi} : std::pair{hi, lo};
}

void expect_same(double a, double b, const std::string& where) {
  if (std::isnan(b)) {
    EXPECT_TRUE(std::isnan(a)) << where;
  } else {
    EXPECT_EQ(a, b) << where;
  }
}

// Every bucket the ring reports, wide or narrow, from its chunk summaries or its samples, is the
// envelope of exactly the samples the bucket's times name: checked against a brute-force scan
// of the truth, after the ring wrapped several times.
TEST(HistoryRing, ThinsEveryWindowToTheEnvelopeOfItsSamples) {
  HistoryRing ring(60 * 512, kHistoryRateHz);  // a minute, a whole number of chunks
  Writer w{ring, {}, 1024};
  w.write(0, 200 * 512);  // 200 s: the ring wrapped more than three times
  ASSERT_EQ(ring.end(), 200u * 512u);
  TraceHistory out;
  for (const auto& [from_s, to_s, buckets] :
       {std::tuple{140.0, 200.0, 500}, std::tuple{141.3, 199.9, 700},
        std::tuple{190.0, 200.0, 1000}, std::tuple{195.0, 196.0, 100}, std::tuple{0.0, 500.0, 300},
        std::tuple{150.0, 160.0, 64}}) {
    ring.read(from_s, to_s, buckets, out);
    ASSERT_FALSE(out.t_s.empty());
    ASSERT_EQ(out.t_s.size() % 2, 0u);
    EXPECT_LE(out.t_s.size(), 2u * static_cast<std::size_t>(buckets) + 2);
    // The oldest sample shown is still in the ring's last minute.
    EXPECT_GE(out.t_s.front(), 140.0 - 1e-9);
    for (std::size_t k = 0; k + 1 < out.t_s.size(); k += 2) {
      const auto start = static_cast<std::uint64_t>(std::llround(out.t_s[k] * kHistoryRateHz));
      const auto stop = static_cast<std::uint64_t>(std::llround(out.t_s[k + 1] * kHistoryRateHz));
      const std::string where = std::to_string(from_s) + "–" + std::to_string(to_s) +
                                " bucket at " + std::to_string(start);
      for (const auto& [trace, scale] :
           {std::pair{&out.base, 1.0}, std::pair{&out.mass, 2.0}, std::pair{&out.force_n, -1.0}}) {
        const auto [first, second] = envelope(w.truth, start, stop, scale);
        expect_same((*trace)[k], first, where);
        expect_same((*trace)[k + 1], second, where);
      }
      // The derived trace lags: its newest `lag` samples are not written yet.
      if (stop + 1024 < ring.end()) {
        const auto [first, second] = envelope(w.truth, start, stop, 3.0);
        expect_same(out.z_m[k], first, where + " (derived)");
        expect_same(out.z_m[k + 1], second, where + " (derived)");
      }
    }
  }
}

TEST(HistoryRing, GivesEverySampleWhenTheWindowHoldsNoMoreThanTheBuckets) {
  HistoryRing ring(1024, kHistoryRateHz);
  Writer w{ring, {}, 64};
  w.write(0, 4096);
  TraceHistory out;
  ring.read(7.0, 7.5, 1000, out);  // 256 samples
  ASSERT_EQ(out.t_s.size(), 256u);
  for (std::size_t i = 0; i < out.t_s.size(); ++i) {
    const auto s = static_cast<std::size_t>(7 * 512) + i;
    EXPECT_DOUBLE_EQ(out.t_s[i], static_cast<double>(s) / kHistoryRateHz);
    expect_same(out.base[i], w.truth[s], "sample " + std::to_string(s));
    expect_same(out.z_m[i], 3 * w.truth[s], "derived sample " + std::to_string(s));
    EXPECT_TRUE(std::isnan(out.b_m[i]));  // never written
  }
}

TEST(HistoryRing, AGapIsNaNAndDerivedValuesOlderThanTheRingAreDropped) {
  HistoryRing ring(128, kHistoryRateHz);
  Writer w{ring, {}, 0};
  w.write(0, 128);
  ring.write_gap(128, 64);
  EXPECT_EQ(ring.end(), 192u);
  TraceHistory out;
  ring.read(0.0, 1.0, 1000, out);
  ASSERT_EQ(out.t_s.size(), 128u);  // 64 … 191: the ring holds 128 samples
  EXPECT_DOUBLE_EQ(out.t_s.front(), 64.0 / kHistoryRateHz);
  for (std::size_t i = 64; i < 128; ++i) EXPECT_TRUE(std::isnan(out.base[i])) << i;
  // A derived value for sample 10, long overwritten, must not land on sample 138's slot.
  const double late = 42.0;
  HistoryRing::BlockWrite stale;
  stale.derived_first = 10;
  stale.derived_count = 1;
  stale.z_m = &late;
  ring.write(stale);
  ring.read(0.0, 1.0, 1000, out);
  for (double z : out.z_m) EXPECT_NE(z, late);
}

TEST(HistoryRing, AnEmptyRingOrWindowGivesNothing) {
  HistoryRing ring(1024, kHistoryRateHz);
  TraceHistory out;
  out.t_s = {1.0};
  ring.read(0.0, 10.0, 100, out);
  EXPECT_TRUE(out.t_s.empty());
  Writer w{ring, {}, 0};
  w.write(0, 512);
  ring.read(5.0, 4.0, 100, out);
  EXPECT_TRUE(out.t_s.empty());
  ring.read(0.0, 1.0, 0, out);
  EXPECT_TRUE(out.t_s.empty());
}

}  // namespace
}  // namespace oscilab::daq
