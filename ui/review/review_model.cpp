#include "ui/review/review_model.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>

#include "analysis/common/input_error.h"
#include "analysis/rfs/motion_spans.h"
#include "analysis/rfs/restoring_force_slices.h"
#include "daq/recording/measurement_mapping.h"

namespace oscilab::ui {
namespace {

// Share of the progress bar the campaign analysis takes; the pass for the slices' points takes
// the rest (one pass of the seven).
constexpr double kCampaignShare = 6.0 / 7.0;

// Thins a stream of points of unknown length by an even stride: keeps every stride-th, and when
// twice the count asked for is kept, drops every other one and doubles the stride; finish()
// ends with at most the count asked for.
class StreamThinner {
 public:
  explicit StreamThinner(std::size_t max_points) : max_(max_points) {}
  void add(double x, double y) {
    if (points_.selected++ % stride_ != 0) return;
    points_.x.push_back(x);
    points_.y.push_back(y);
    if (max_ > 0 && points_.x.size() >= 2 * max_) halve();
  }
  ScatterPoints finish() {
    while (max_ > 0 && points_.x.size() > max_) halve();
    return std::move(points_);
  }

 private:
  void halve() {
    std::size_t kept = 0;
    for (std::size_t i = 0; i < points_.x.size(); i += 2, ++kept) {
      points_.x[kept] = points_.x[i];
      points_.y[kept] = points_.y[i];
    }
    points_.x.resize(kept);
    points_.y.resize(kept);
    stride_ *= 2;  // those kept are the multiples of the stride, as the next ones will be
  }

  std::size_t max_;
  std::size_t stride_ = 1;
  ScatterPoints points_;
};

}  // namespace

ReviewAnalysis analyze_review(
    const std::vector<std::shared_ptr<const daq::OpenedRecording>>& recordings,
    const analysis::PipelineSettings& settings, const ProgressFn& progress,
    const CancelToken& cancel) {
  ReviewAnalysis out;
  std::vector<analysis::MeasurementChannels> channels;
  for (const auto& recording : recordings) {
    if (!recording || !recording->samples) continue;
    try {
      channels.push_back(recording->samples->measurement_channels());
      out.recordings.push_back(recording);
    } catch (const InputError& error) {
      out.errors.emplace_back(error.what());
    }
  }
  const ProgressFn campaign_progress = [&progress](double fraction) {
    if (progress) progress(kCampaignShare * fraction);
  };
  analysis::OfflineRetention retention;
  retention.motion = false;  // a loop is made again from its window
  retention.cycles = false;
  out.cycles.resize(channels.size());
  retention.each_cycle = [&out](std::size_t record, const analysis::CycleFit& cycle) {
    out.cycles[record].push_back({cycle.start_s, cycle.end_s, cycle.edc_j});  // its thread's
  };
  try {
    out.campaign =
        analysis::analyze_campaign(channels, settings, campaign_progress, cancel, retention);
    if (out.campaign.status == JobStatus::Ok && out.campaign.stiffness) {
      out.slice_points =
          slice_points(analysis::campaign_motion_pass(out.campaign, channels, cancel), out.campaign,
                       kSlicePointsShown,
                       kSlicePointsShown / std::max<std::size_t>(out.campaign.damping.size(), 1));
      if (cancel.cancelled()) out.campaign.status = JobStatus::Cancelled;
    }
  } catch (const std::exception& error) {  // InputError: a record the core cannot analyse
    out.errors.emplace_back(error.what());
    out.campaign = analysis::CampaignAnalysis{};
    out.campaign.settings = settings;
    out.campaign.status = JobStatus::InvalidInput;
    out.recordings.clear();
    out.cycles.clear();
    out.slice_points = {};
    return out;
  }
  if (progress && out.campaign.status == JobStatus::Ok) progress(1.0);
  return out;
}

SlicePoints slice_points(const analysis::MotionPass& pass,
                         const analysis::CampaignAnalysis& campaign, std::size_t max_stiffness,
                         std::size_t max_damping) {
  SlicePoints points;
  if (!campaign.stiffness) return points;
  const double band_m_s = campaign.stiffness->velocity_band_m_s;
  const analysis::PolynomialFit& fit = campaign.stiffness->fit;
  StreamThinner stiffness(max_stiffness);
  std::vector<StreamThinner> damping(campaign.damping.size(), StreamThinner(max_damping));
  pass([&](const analysis::MotionSignals& s, double record_end_s) {
    analysis::for_each_slice_sample(
        s, record_end_s, campaign.settings.edge_trim_s, [&](Eigen::Index i) {
          if (std::abs(s.z_dot_m_s[i]) < band_m_s) stiffness.add(s.z_m[i], s.restoring_force_n[i]);
          for (std::size_t d = 0; d < damping.size(); ++d) {
            const analysis::DampingSlice& slice = campaign.damping[d];
            if (std::abs(s.z_m[i] - slice.z_center_m) < slice.position_band_m) {
              damping[d].add(s.z_dot_m_s[i], s.restoring_force_n[i] - fit.value(s.z_m[i]));
            }
          }
        });
  });
  points.stiffness = stiffness.finish();
  for (StreamThinner& d : damping) points.damping.push_back(d.finish());
  return points;
}

std::vector<LevelRow> level_rows(int record, const std::string& record_name,
                                 const std::vector<analysis::LevelResult>& levels,
                                 bool per_unit_mass) {
  std::vector<LevelRow> rows;
  rows.reserve(levels.size());
  for (std::size_t i = 0; i < levels.size(); ++i) {
    const analysis::LevelResult& level = levels[i];
    LevelRow row;
    row.key = {record, int(i)};
    row.record = record_name;
    row.well = level.well;
    row.f0_n = level.f0_n;
    row.edc_mean_j = level.edc_mean_j;
    row.edc_std_j = level.edc_std_j;
    row.cycles = level.cycles;
    row.flags = level.flags();
    if (per_unit_mass) row.flags += row.flags.empty() ? "per-unit-mass" : ";per-unit-mass";
    rows.push_back(std::move(row));
  }
  return rows;
}

std::vector<LevelRow> level_rows(const analysis::CampaignAnalysis& campaign) {
  std::vector<LevelRow> rows;
  for (std::size_t r = 0; r < campaign.records.size(); ++r) {
    const analysis::RecordAnalysis& record = campaign.records[r];
    for (LevelRow& row : level_rows(int(r), record.name, record.levels, record.per_unit_mass)) {
      rows.push_back(std::move(row));
    }
  }
  return rows;
}

const analysis::LevelResult* find_level(const analysis::CampaignAnalysis& campaign, LevelKey key) {
  if (key.record < 0 || std::size_t(key.record) >= campaign.records.size()) return nullptr;
  const auto& levels = campaign.records[std::size_t(key.record)].levels;
  if (key.level < 0 || std::size_t(key.level) >= levels.size()) return nullptr;
  return &levels[std::size_t(key.level)];
}

std::vector<LevelKey> overview_levels(const analysis::CampaignAnalysis& campaign) {
  std::vector<LevelKey> out;
  for (const analysis::Well well : {analysis::Well::Positive, analysis::Well::Negative}) {
    std::vector<std::pair<double, LevelKey>> levels;  // by f0
    for (std::size_t r = 0; r < campaign.records.size(); ++r) {
      const std::vector<analysis::LevelResult>& record = campaign.records[r].levels;
      for (std::size_t l = 0; l < record.size(); ++l) {
        if (record[l].well == well && record[l].usable()) {
          levels.push_back({record[l].f0_n, {static_cast<int>(r), static_cast<int>(l)}});
        }
      }
    }
    if (levels.empty()) continue;
    std::sort(levels.begin(), levels.end());
    std::vector<std::size_t> picks = {0, levels.size() / 2, levels.size() - 1};
    picks.erase(std::unique(picks.begin(), picks.end()), picks.end());
    for (std::size_t k : picks) out.push_back(levels[k].second);
  }
  return out;
}

double level_cursor_time_s(const analysis::LevelResult& level) {
  return 0.5 * (level.start_s + level.end_s);
}

TimeWindow level_time_window(const analysis::LevelResult& level, double margin_rel) {
  const double margin_s = margin_rel * (level.end_s - level.start_s);
  return {level.start_s - margin_s, level.end_s + margin_s};
}

LevelLoop level_loop(const analysis::MotionSignals& motion, const Eigen::VectorXd& force_n,
                     const analysis::LevelResult& level) {
  LevelLoop loop;
  loop.well = level.well;
  loop.cycles = level.cycles;
  const Eigen::Index n = std::min(
      {motion.t_s.size(), motion.z_m.size(), force_n.size(), motion.restoring_force_n.size()});
  const double* t = motion.t_s.data();
  const Eigen::Index first = std::lower_bound(t, t + n, level.start_s) - t;
  for (Eigen::Index i = first; i < n && t[i] <= level.end_s; ++i) {
    if (!std::isfinite(motion.z_m[i]) || !std::isfinite(force_n[i]) ||
        !std::isfinite(motion.restoring_force_n[i])) {
      continue;
    }
    loop.t_s.push_back(t[i]);
    loop.z_m.push_back(motion.z_m[i]);
    loop.f_n.push_back(force_n[i]);
  }
  return loop;
}

LevelLoop level_loop(const daq::OpenedRecording& recording,
                     const analysis::PipelineSettings& settings,
                     const analysis::LevelResult& level) {
  const double rate_hz = recording.sidecar.sample_rate_hz;
  const Eigen::Index n = recording.sample_count();
  if (!recording.samples || !(rate_hz > 0.0) || n == 0) return {};
  Eigen::Index first =
      std::clamp<Eigen::Index>(Eigen::Index(std::ceil(level.start_s * rate_hz)), 0, n);
  const Eigen::Index end =
      std::clamp<Eigen::Index>(Eigen::Index(std::floor(level.end_s * rate_hz)) + 1, first, n);
  if (end == first) return {};
  analysis::LevelResult shown = level;
  if (end - first > kLoopSamples) {  // the last kLoopSamples, its cycles in proportion
    shown.cycles =
        int(std::lround(double(level.cycles) * double(kLoopSamples) / double(end - first)));
    first = end - kLoopSamples;
    shown.start_s = double(first) / rate_hz;
  }
  const analysis::SampleRange range =
      analysis::motion_window_range(first, end, n, rate_hz, settings);
  const std::string file = recording.source_path.empty() ? "recording" : recording.source_path;
  const analysis::MeasurementChannels window = daq::measurement_rows(
      recording.sidecar, file, recording.samples->read(range.first, range.end - range.first));
  const analysis::WindowMotion motion =
      analysis::window_motion(window, range.first, first, end, settings);
  return level_loop(motion.motion, motion.force_n, shown);
}

double loop_area_j(const std::vector<double>& z_m, const std::vector<double>& f_n) {
  double area_j = 0.0;
  for (std::size_t i = 1; i < std::min(z_m.size(), f_n.size()); ++i) {
    area_j += 0.5 * (f_n[i] + f_n[i - 1]) * (z_m[i] - z_m[i - 1]);
  }
  return area_j;
}

std::string value_with_error(double value, double error) {
  char text[64];
  std::snprintf(text, sizeof text, "%.4g \u00b1 %.2g", value, error);
  return text;
}

std::string stiffness_fit_text(const analysis::StiffnessSlice& slice, bool per_unit_mass) {
  const auto& c = slice.fit.coefficients;
  const auto& e = slice.fit.std_errors;
  const auto coefficient = [&](Eigen::Index i, double sign) {
    const double value = i < c.size() ? sign * c[i] : 0.0;
    const double error = i < e.size() ? e[i] : 0.0;
    return value_with_error(value, error);
  };
  // N/m^k, or N/(kg m^k) per unit mass.
  const auto unit = [&](const char* length) {
    if (!per_unit_mass) return std::string("N") + (*length ? std::string("/") + length : "");
    return std::string("N/(kg") + (*length ? std::string(" ") + length : "") + ")";
  };
  // Eq. (2): K(z) = k3 z³ + k2 z² − k1 z + k0, so k1 = −c1.
  std::string text = "K(z) = k\u2083z\u00b3 + k\u2082z\u00b2 \u2212 k\u2081z + k\u2080 (eq. 2): ";
  text += "k\u2083 = " + coefficient(3, 1.0) + " " + unit("m\u00b3") + ",  ";
  text += "k\u2082 = " + coefficient(2, 1.0) + " " + unit("m\u00b2") + ",  ";
  text += "k\u2081 = " + coefficient(1, -1.0) + " " + unit("m") + ",  ";
  text += "k\u2080 = " + coefficient(0, 1.0) + " " + unit("");
  char tail[96];
  std::snprintf(tail, sizeof tail, "  (rms residual %.3g %s, %ld samples)", slice.fit.residual_rms,
                per_unit_mass ? "N/kg" : "N", long(slice.fit.samples));
  return text + tail;
}

}  // namespace oscilab::ui
