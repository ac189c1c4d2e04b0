#include "analysis/pipeline/offline_analysis.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <optional>

#include "analysis/common/input_error.h"
#include "analysis/common/parallel_for.h"
#include "analysis/rfs/motion_spans.h"
#include "analysis/signal/gap_fill.h"

namespace oscilab::analysis {
namespace {

// A record is a sine test when one tone holds most of the base channel's power.
constexpr double kSineToneFraction = 0.5;

// Real roots of the fitted cubic where K' > 0 (stable equilibria), for the damping slices.
std::vector<double> stable_zeros(const PolynomialFit& fit, double lo, double hi) {
  std::vector<double> zeros;
  constexpr int kSteps = 2000;
  double previous = fit.value(lo);
  for (int i = 1; i <= kSteps; ++i) {
    const double z = lo + (hi - lo) * i / kSteps;
    const double value = fit.value(z);
    if (previous < 0.0 && value >= 0.0) {  // K rising through zero: stable
      double a = z - (hi - lo) / kSteps, b = z;
      for (int k = 0; k < 60; ++k) {
        const double m = 0.5 * (a + b);
        (fit.value(m) < 0.0 ? a : b) = m;
      }
      zeros.push_back(0.5 * (a + b));
    }
    previous = value;
  }
  return zeros;
}

}  // namespace

StreamSetup stream_setup(const MeasurementChannels& channels) {
  StreamSetup setup;
  setup.sample_rate_hz = channels.sample_rate_hz;
  setup.mass_kg = channels.mass_kg.value_or(1.0);
  setup.base_quantity = channels.base_quantity;
  setup.mass_quantity = channels.mass_quantity;
  setup.mass_is_relative = channels.mass_is_relative;
  setup.excitation_freq_hz = channels.excitation_freq_hz.value_or(0.0);
  setup.level_windows = channels.level_windows;
  setup.well_hint_positive = channels.well_hint_positive;
  return setup;
}

RecordAnalysis analyze_record(const MeasurementChannels& channels, const PipelineSettings& settings,
                              const CancelToken& cancel, const OfflineRetention& retention) {
  settings.validate();
  const Eigen::Index n = channels.sample_count();
  if ((!channels.source && channels.base.size() != channels.mass.size()) || n < 16) {
    throw InputError(channels.name + ": base and mass channels need the same, non-trivial length");
  }
  RecordAnalysis out;
  out.name = channels.name;
  out.sample_count = n;
  out.per_unit_mass = !channels.mass_kg.has_value();
  out.motion.z_absolute = channels.mass_quantity == MotionQuantity::Displacement;
  if (out.per_unit_mass) {
    out.notes.push_back(
        "no mass_kg in the sidecar: forces are per unit mass (N/kg) and energies "
        "per unit mass (J/kg)");
  }

  StreamSetup setup = stream_setup(channels);

  // The tone is looked for only where the sidecar leaves the excitation open.
  const bool known = !channels.excitation_type.empty() &&
                     (channels.excitation_type != "stepped-sine" || channels.excitation_freq_hz);
  if (!known) {
    if (!channels.source && n <= kToneSamples) {
      out.tone = dominant_tone(channels.base, channels.sample_rate_hz);
    } else {
      Eigen::VectorXd base(std::min(n, kToneSamples)), mass(base.size());
      read_samples(*channels.open(), base.data(), mass.data(), base.size(), channels.name);
      fill_non_finite(base);
      out.tone = dominant_tone(base, channels.sample_rate_hz);
    }
  }
  if (channels.excitation_freq_hz) {
    setup.excitation_freq_hz = *channels.excitation_freq_hz;
  } else if (!known || channels.excitation_type == "stepped-sine") {
    setup.excitation_freq_hz = out.tone.freq_hz;
    out.frequency_detected = true;
  }
  out.stepped_sine =
      channels.excitation_type == "stepped-sine" ||
      (channels.excitation_type.empty() && out.tone.power_fraction >= kSineToneFraction);
  if (out.frequency_detected && out.stepped_sine) {
    out.notes.push_back("excitation frequency detected from the base channel: " +
                        std::to_string(setup.excitation_freq_hz) + " Hz");
  }
  if (out.stepped_sine && channels.level_windows.empty()) {
    out.notes.push_back("levels detected from the force amplitude (no levels in the sidecar)");
  }
  out.setup = setup;

  // Samples of invalid intervals (a live recording's gaps, bad samples) may be non-finite: each
  // chunk's are filled before it is pushed, and every result that touches them is left out.
  std::optional<MeasurementPipeline> pipeline;
  if (out.stepped_sine && setup.excitation_freq_hz > 0) {
    pipeline.emplace(settings, setup, retention.cycles);
    for (const TimeInterval& interval : channels.excluded) {
      pipeline->exclude(interval.start_s, interval.end_s);
    }
  }
  long filled_samples = 0;
  if (pipeline || !channels.excluded.empty()) {
    // Streamed in chunks, as a live stream arrives (the result does not depend on the chunks).
    constexpr Eigen::Index kChunk = 8192;
    Eigen::VectorXd base(kChunk), mass(kChunk);
    const std::unique_ptr<ChannelReader> reader = channels.open();
    for (Eigen::Index first = 0; first < n; first += kChunk) {
      if (cancel.cancelled()) return out;
      const Eigen::Index count = std::min(kChunk, n - first);
      read_samples(*reader, base.data(), mass.data(), count, channels.name);
      if (!base.head(count).array().isFinite().all() ||
          !mass.head(count).array().isFinite().all()) {
        Eigen::VectorXd b = base.head(count), m = mass.head(count);
        filled_samples += fill_non_finite(b) + fill_non_finite(m);
        base.head(count) = b;
        mass.head(count) = m;
      }
      if (pipeline) {
        pipeline->push(first, base.data(), mass.data(), static_cast<int>(count));
        if (retention.each_cycle) {
          for (const CycleFit& cycle : pipeline->last_completed()) retention.each_cycle(0, cycle);
        }
      }
    }
  }
  if (!channels.excluded.empty()) {
    out.notes.push_back(std::to_string(channels.excluded.size()) +
                        " invalid interval(s) in the sidecar left out (" +
                        std::to_string(filled_samples) + " non-finite samples)");
  }
  if (pipeline) {
    pipeline->finish();
    out.cycle_count = pipeline->cycle_count();
    out.cycles = pipeline->cycles();
    out.levels = pipeline->levels();
    if (pipeline->excluded_cycles() > 0) {
      out.notes.push_back(std::to_string(pipeline->excluded_cycles()) +
                          " cycle(s) touching invalid intervals left out of the EDC");
    }
    for (std::string& note : degenerate_level_notes(out.levels)) {
      out.notes.push_back(std::move(note));
    }
  }
  if (cancel.cancelled() || !retention.motion) return out;
  // The spans in place: one span is the whole record's motion, more fill their parts of it.
  Eigen::Index filled = 0;
  for_each_motion_span(
      channels, settings,
      [&](const MotionSignals& span, double) {
        if (span.t_s.size() == n) {
          out.motion = span;
          return;
        }
        MotionSignals& m = out.motion;
        if (filled == 0) {
          m.t_s.resize(n);
          m.z_m.resize(n);
          m.z_dot_m_s.resize(n);
          m.restoring_force_n.resize(n);
        }
        const Eigen::Index k = span.t_s.size();
        m.t_s.segment(filled, k) = span.t_s;
        m.z_m.segment(filled, k) = span.z_m;
        m.z_dot_m_s.segment(filled, k) = span.z_dot_m_s;
        m.restoring_force_n.segment(filled, k) = span.restoring_force_n;
        filled += k;
      },
      cancel);
  return out;
}

std::string no_measured_level_reason(const RecordAnalysis& record) {
  if (!record.stepped_sine) return "";
  if (record.levels.empty()) {
    return record.name +
           ": no stepped-sine level found in the record (give the levels in the "
           "sidecar, or check the base channel)";
  }
  if (std::any_of(record.levels.begin(), record.levels.end(),
                  [](const LevelResult& level) { return level.measured(); })) {
    return "";
  }
  std::string reason = record.name + ": no usable level";
  const std::vector<std::string> notes = degenerate_level_notes(record.levels);
  if (notes.empty()) return reason + ": no level has steady cycles";
  for (std::size_t i = 0; i < notes.size(); ++i) reason += (i == 0 ? ": " : "; ") + notes[i];
  return reason;
}

void require_measured_levels(const CampaignAnalysis& campaign) {
  for (const RecordAnalysis& record : campaign.records) {
    if (std::string reason = no_measured_level_reason(record); !reason.empty()) {
      throw InputError(reason);
    }
  }
}

namespace {

// The records the slices stack (slice_records' rule, from what every record knows): those that
// measure z itself; when none does, every record (without a position the integrated velocity's
// mean is lost to the integration's high-pass: z is z − z̄ already).
std::vector<std::size_t> slice_record_indices(const std::vector<RecordAnalysis>& records) {
  std::vector<std::size_t> absolute, all;
  for (std::size_t i = 0; i < records.size(); ++i) {
    if (records[i].sample_count == 0 && records[i].motion.t_s.size() == 0) continue;
    all.push_back(i);
    if (records[i].motion.z_absolute) absolute.push_back(i);
  }
  return absolute.empty() ? all : absolute;
}

}  // namespace

std::vector<const MotionSignals*> slice_records(const std::vector<RecordAnalysis>& records) {
  std::vector<const MotionSignals*> signals;
  for (const std::size_t i : slice_record_indices(records)) {
    if (records[i].motion.t_s.size() > 0) signals.push_back(&records[i].motion);
  }
  return signals;
}

MotionPass campaign_motion_pass(const CampaignAnalysis& campaign,
                                const std::vector<MeasurementChannels>& records,
                                const CancelToken& cancel) {
  return [&campaign, &records, cancel](const MotionSpanVisit& visit) {
    for (const std::size_t i : slice_record_indices(campaign.records)) {
      const MotionSignals& kept = campaign.records[i].motion;
      if (kept.t_s.size() > 0) {
        visit(kept, kept.t_s[kept.t_s.size() - 1]);
      } else if (i < records.size()) {
        for_each_motion_span(records[i], campaign.settings, visit, cancel);
      }
    }
  };
}

CampaignAnalysis analyze_campaign(const std::vector<MeasurementChannels>& records,
                                  const PipelineSettings& settings, const ProgressFn& progress,
                                  const CancelToken& cancel, const OfflineRetention& retention) {
  settings.validate();
  // A cancelled campaign keeps nothing of what was made, only its settings and status.
  const auto cancelled = [&settings] {
    CampaignAnalysis out;
    out.settings = settings;
    out.status = JobStatus::Cancelled;
    return out;
  };
  CampaignAnalysis campaign;
  campaign.settings = settings;
  // The records are independent until the restoring-force slices, which pool them: one per
  // thread, the results in the order given, the first error (in that order) rethrown.
  campaign.records.resize(records.size());
  std::vector<std::exception_ptr> errors(records.size());
  std::mutex progress_mutex;
  std::size_t done = 0;
  parallel_for(records.size(), 0, [&](std::size_t i) {
    if (cancel.cancelled()) return;
    try {
      OfflineRetention of_record = retention;
      if (retention.each_cycle) {
        of_record.each_cycle = [&retention, i](std::size_t, const CycleFit& cycle) {
          retention.each_cycle(i, cycle);
        };
      }
      campaign.records[i] = analyze_record(records[i], settings, cancel, of_record);
    } catch (...) {
      errors[i] = std::current_exception();
    }
    const std::lock_guard lock(progress_mutex);
    ++done;
    if (progress) progress(static_cast<double>(done) / static_cast<double>(records.size() + 1));
  });
  for (const std::exception_ptr& error : errors) {
    if (error) std::rethrow_exception(error);
  }
  if (cancel.cancelled()) return cancelled();
  const std::vector<std::size_t> sliced = slice_record_indices(campaign.records);
  campaign.z_about_mean =
      !sliced.empty() && std::none_of(campaign.records.begin(), campaign.records.end(),
                                      [](const RecordAnalysis& r) { return r.motion.z_absolute; });
  Eigen::Index max_samples = 0;
  for (const std::size_t i : sliced) max_samples += campaign.records[i].sample_count;
  const MotionPass pass = campaign_motion_pass(campaign, records, cancel);
  if (sliced.empty()) {
    campaign.rfs_message = "no record to slice";
  } else {
    try {
      campaign.stiffness = stiffness_slice(pass, max_samples, settings);
      const std::vector<double> zeros = stable_zeros(
          campaign.stiffness->fit, campaign.stiffness->z_min_m, campaign.stiffness->z_max_m);
      campaign.damping = damping_slices(pass, max_samples, *campaign.stiffness, zeros, settings);
    } catch (const InputError& error) {
      campaign.rfs_message = error.what();
    }
  }
  if (cancel.cancelled()) return cancelled();  // during the slices
  if (progress) progress(1.0);
  return campaign;
}

nlohmann::json campaign_summary(const CampaignAnalysis& campaign) {
  using nlohmann::json;
  json summary;
  summary["settings"] = campaign.settings.to_json();
  json records = json::array();
  for (const RecordAnalysis& r : campaign.records) {
    json levels = json::array();
    for (const LevelResult& level : r.levels) {
      levels.push_back({{"well", to_string(level.well)},
                        {"f0_n", level.f0_n},
                        {"edc_mean_j", level.edc_mean_j},
                        {"edc_std_j", level.edc_std_j},
                        {"edc_noise_floor_j", level.edc_noise_floor_j},
                        {"cycles", level.cycles},
                        {"transient_cycles", level.transient_cycles},
                        {"flags", level.flags()}});
    }
    records.push_back({{"name", r.name},
                       {"sample_rate_hz", r.setup.sample_rate_hz},
                       {"excitation_freq_hz", r.setup.excitation_freq_hz},
                       {"frequency_detected", r.frequency_detected},
                       {"tone_power_fraction", r.tone.power_fraction},
                       {"stepped_sine", r.stepped_sine},
                       {"per_unit_mass", r.per_unit_mass},
                       {"cycles", r.cycle_count},
                       {"levels", levels},
                       {"notes", r.notes}});
  }
  summary["records"] = records;
  if (campaign.stiffness) {
    const StiffnessSlice& s = *campaign.stiffness;
    const auto c = [&](int i) {
      return i < s.fit.coefficients.size() ? s.fit.coefficients[i] : 0.0;
    };
    const auto e = [&](int i) { return i < s.fit.std_errors.size() ? s.fit.std_errors[i] : 0.0; };
    // Eq. (2): K(z) = k3 z³ + k2 z² − k1 z + k0.
    summary["stiffness_fit"] = {{"k3_n_m3", c(3)},
                                {"k3_n_m3_std", e(3)},
                                {"k2_n_m2", c(2)},
                                {"k2_n_m2_std", e(2)},
                                {"k1_n_m", -c(1)},
                                {"k1_n_m_std", e(1)},
                                {"k0_n", c(0)},
                                {"k0_n_std", e(0)},
                                {"residual_rms_n", s.fit.residual_rms},
                                {"samples", s.fit.samples},
                                {"velocity_band_m_s", s.velocity_band_m_s},
                                {"z_min_m", s.z_min_m},
                                {"z_max_m", s.z_max_m},
                                {"z_about_mean", campaign.z_about_mean}};
    json damping = json::array();
    for (const DampingSlice& d : campaign.damping) {
      damping.push_back({{"z_center_m", d.z_center_m},
                         {"position_band_m", d.position_band_m},
                         {"bins", d.bins.size()}});
    }
    summary["damping_slices"] = damping;
  } else {
    summary["stiffness_fit"] = nullptr;
    summary["rfs_message"] = campaign.rfs_message;
  }
  return summary;
}

}  // namespace oscilab::analysis
