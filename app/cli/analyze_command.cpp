// oscilab-cli analyze REC... --edc EDC.csv [--rfs RFS.csv] [--summary S.json] (contract §2)
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <optional>

#include "analysis/common/input_error.h"
#include "analysis/edc/well.h"
#include "analysis/identification/campaign_model.h"
#include "analysis/model/model_json.h"
#include "analysis/pipeline/edc_table.h"
#include "analysis/pipeline/offline_analysis.h"
#include "analysis/pipeline/result_units.h"
#include "app/cli/campaign_input.h"
#include "app/cli/commands.h"
#include "app/cli/cycle_spool.h"
#include "app/cli/option_parsing.h"
#include "app/cli/output_files.h"
#include "daq/recording/measurement_mapping.h"

namespace oscilab::cli {
namespace {

struct AnalyzeOptions {
  std::vector<std::string> recordings;
  std::string edc_path;
  std::string rfs_path;
  std::string damping_path;
  std::string cycles_path;
  std::string summary_path;
  std::string model_out_path;
  std::string model = "paper";
  double freq_hz = 0.0;
  std::string well;
  bool detect_levels = false;
  bool timing = false;
  analysis::PipelineSettings settings;
};

// Each table is written to `path` (a temporary, OutputFiles) and named by its `target`.
std::FILE* open_output(const std::string& path, const std::string& target) {
  std::FILE* file = std::fopen(path.c_str(), "w");
  if (!file) throw InputError(target + ": cannot write: " + std::strerror(errno));
  return file;
}

void close_output(std::FILE* file, const std::string& target) {
  const bool failed = std::ferror(file) != 0;
  if (std::fclose(file) != 0 || failed) {
    throw InputError(target + ": write failed: " + std::strerror(errno));
  }
}

// Writes `rows` as CSV with a header of `columns`' names (docs/contracts.md §3).
template <class Row>
void write_table(const std::vector<analysis::TableColumn<Row>>& columns,
                 const std::vector<Row>& rows, const std::string& path, const std::string& target) {
  std::FILE* out = open_output(path, target);
  std::fprintf(out, "%s\n", analysis::csv_header(columns).c_str());
  for (const Row& row : rows) std::fprintf(out, "%s\n", analysis::csv_line(columns, row).c_str());
  close_output(out, target);
}

void write_rfs(const analysis::CampaignAnalysis& campaign, const std::string& path,
               const std::string& target) {
  if (!campaign.stiffness) throw InputError("--rfs: no stiffness slice: " + campaign.rfs_message);
  std::FILE* out = open_output(path, target);
  std::fprintf(out, "z_m,restoring_force_n,samples\n");
  for (const auto& bin : campaign.stiffness->bins) {
    std::fprintf(out, "%.9g,%.9g,%d\n", bin.x, bin.force_n, bin.samples);
  }
  close_output(out, target);
}

void write_damping(const analysis::CampaignAnalysis& campaign, const std::string& path,
                   const std::string& target) {
  std::FILE* out = open_output(path, target);
  std::fprintf(out, "z_center_m,z_dot_m_s,damping_force_n,samples\n");
  for (const auto& slice : campaign.damping) {
    for (const auto& bin : slice.bins) {
      std::fprintf(out, "%.9g,%.9g,%.9g,%d\n", slice.z_center_m, bin.x, bin.force_n, bin.samples);
    }
  }
  close_output(out, target);
}

void print_report(const analysis::CampaignAnalysis& campaign) {
  for (const auto& record : campaign.records) {
    if (record.stepped_sine) {
      std::printf("%s: stepped sine at %.4f Hz%s%s\n", record.name.c_str(),
                  record.setup.excitation_freq_hz, record.frequency_detected ? " (detected)" : "",
                  record.per_unit_mass ? ", per unit mass" : "");
    } else {
      std::printf(
          "%s: broadband excitation (no single tone holds %.0f%% of the base power): no "
          "EDC levels, restoring force only\n",
          record.name.c_str(), 100.0 * record.tone.power_fraction);
    }
    if (record.levels.empty()) continue;
    const std::string force = "f0 [" + analysis::result_unit("N", record.per_unit_mass) + "]";
    const std::string energy = "[" + analysis::result_unit("J", record.per_unit_mass) + "]";
    std::printf("  %-10s %9s %12s %11s %12s %6s  %s\n", "well", force.c_str(),
                ("EDC " + energy).c_str(), ("std " + energy).c_str(), ("floor " + energy).c_str(),
                "cycles", "flags");
    for (const auto& l : record.levels) {
      std::printf("  %-10s %9.3f %12.5g %11.3g %12.3g %6d  %s\n", to_string(l.well).c_str(), l.f0_n,
                  l.edc_mean_j, l.edc_std_j, l.edc_noise_floor_j, l.cycles, l.flags().c_str());
    }
  }
  // Each note once, with the records it concerns.
  for (const analysis::SharedNote& note : analysis::shared_notes(campaign)) {
    std::printf("note: %s\n", analysis::note_text(note, campaign.records.size()).c_str());
  }
  if (campaign.stiffness) {
    const auto& c = campaign.stiffness->fit.coefficients;
    const auto& e = campaign.stiffness->fit.std_errors;
    const bool per_kg = analysis::mass_basis(campaign) == analysis::MassBasis::PerUnitMass;
    std::printf(
        "stiffness K(z) = k3 z^3 + k2 z^2 - k1 z + k0 (eq. (2)) from %ld samples with "
        "|z_dot| < %.3g m/s:\n  k3 = %.4g ± %.2g %s, k2 = %.4g ± %.2g %s, "
        "k1 = %.4g ± %.2g %s, k0 = %.4g ± %.2g %s\n",
        static_cast<long>(campaign.stiffness->fit.samples), campaign.stiffness->velocity_band_m_s,
        c[3], e[3], per_kg ? "N/(kg m^3)" : "N/m^3", c[2], e[2], per_kg ? "N/(kg m^2)" : "N/m^2",
        -c[1], e[1], per_kg ? "N/(kg m)" : "N/m", c[0], e[0], per_kg ? "N/kg" : "N");
    const auto& slice = *campaign.stiffness;
    const double boundary = campaign.settings.well_boundary_m;
    if (campaign.z_about_mean) {
      std::printf("  note: %s\n", analysis::kZAboutMeanNote);
    } else if (!(slice.z_min_m < boundary && slice.z_max_m > boundary)) {
      std::printf(
          "  warning: the slice covers z from %.4f to %.4f m only, one side of the well "
          "boundary (z = %g m):\n  the cubic is extrapolated outside it and poorly "
          "determined; analyse both wells or a cross-well record together\n",
          slice.z_min_m, slice.z_max_m, boundary);
    }
  } else {
    std::printf("no stiffness slice: %s\n", campaign.rfs_message.c_str());
  }
}

void run(const AnalyzeOptions& options) {
  const std::vector<std::string> inputs = recordings_and_sidecars(options.recordings);
  refuse_output_over_inputs(options.edc_path, "--edc", inputs);
  refuse_output_over_inputs(options.cycles_path, "--cycles", inputs);
  refuse_output_over_inputs(options.rfs_path, "--rfs", inputs);
  refuse_output_over_inputs(options.damping_path, "--damping", inputs);
  refuse_output_over_inputs(options.summary_path, "--summary", inputs);
  refuse_output_over_inputs(options.model_out_path, "--model-out", inputs);
  daq::MappingOverrides overrides;
  if (options.freq_hz > 0) overrides.excitation_freq_hz = options.freq_hz;
  if (!options.well.empty()) {
    overrides.well_positive = analysis::well_from_string(options.well) == analysis::Well::Positive;
  }
  overrides.ignore_sidecar_levels = options.detect_levels;
  // The starting model of --model-out is read before the recordings: a bad one costs no analysis.
  std::optional<analysis::Model> start_model;
  if (!options.model_out_path.empty()) start_model = analysis::model_from_spec(options.model);
  InputTimes times;
  // The records stay in their files and only the tables' contents are kept, so that a record
  // of any length is analysed in bounded memory; the cycles of --cycles go to a spool as they
  // are fitted.
  InputStageOptions input;
  input.streamed = true;
  input.retention.motion = false;
  input.retention.cycles = false;
  std::optional<CycleSpool> cycles;
  if (!options.cycles_path.empty()) {
    cycles.emplace(options.cycles_path);
    input.retention.each_cycle = [&cycles](std::size_t record, const analysis::CycleFit& cycle) {
      cycles->add(record, cycle);
    };
  }
  const analysis::CampaignAnalysis campaign =
      run_input_stage(options.recordings, overrides, options.settings, &times, input);
  const auto output_start = std::chrono::steady_clock::now();
  print_report(campaign);
  // A stepped-sine record of which no level measures anything (a dead channel, swapped roles,
  // levels beyond its end) is bad input: the report above shows its flags, no table is written.
  analysis::require_measured_levels(campaign);
  // Every output complete before any is in place: a failure leaves none of them.
  OutputFiles outputs;
  if (!options.edc_path.empty()) {
    write_table(analysis::edc_table_columns(), analysis::edc_table_rows(campaign),
                outputs.add(options.edc_path), options.edc_path);
  }
  if (cycles) {
    std::vector<std::string> names;
    for (const analysis::RecordAnalysis& record : campaign.records) names.push_back(record.name);
    cycles->write(names, outputs.add(options.cycles_path));
  }
  if (!options.rfs_path.empty()) {
    if (!campaign.stiffness) throw InputError("--rfs: no stiffness slice: " + campaign.rfs_message);
    write_rfs(campaign, outputs.add(options.rfs_path), options.rfs_path);
  }
  if (!options.damping_path.empty()) {
    write_damping(campaign, outputs.add(options.damping_path), options.damping_path);
  }
  if (!options.summary_path.empty()) {
    std::ofstream out(outputs.add(options.summary_path));
    out << analysis::campaign_summary(campaign).dump(2) << '\n';
    out.flush();
    if (!out) throw InputError(options.summary_path + ": write failed: " + std::strerror(errno));
  }
  if (!options.model_out_path.empty()) {
    // The lab's model: the recordings' mass and the stiffness slice's K(z), the friction and
    // damping of --model as a start for a fit or a diagnosis.
    if (!campaign.stiffness) {
      throw InputError("--model-out: the records give no stiffness slice to take K(z) from: " +
                       campaign.rfs_message);
    }
    std::vector<std::string> notes;
    const analysis::Model model =
        analysis::campaign_model(*start_model, campaign, analysis::StiffnessSource::Rfs, notes);
    analysis::save_model(model, outputs.add(options.model_out_path));
    for (const std::string& note : notes) std::printf("model: %s\n", note.c_str());
    std::printf("model written to %s\n", options.model_out_path.c_str());
  }
  outputs.commit();
  if (options.timing) {
    const double output_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - output_start).count();
    const double total_s = times.read_s + times.analysis_s + output_s;
    std::printf(
        "timing: read %.2f ms, analysis %.2f ms, output %.2f ms; %.2f ms for %.1f s of signal "
        "(%.0fx real time, start-up not included)\n",
        1e3 * times.read_s, 1e3 * times.analysis_s, 1e3 * output_s, 1e3 * total_s, times.signal_s,
        times.signal_s / total_s);
  }
}

}  // namespace

void add_analyze_command(CLI::App& app) {
  auto o = std::make_shared<AnalyzeOptions>();
  CLI::App* command = app.add_subcommand(
      "analyze",
      "Measurement analysis (§3, §4.1): per-level energy dissipated per cycle of "
      "stepped-sine records and the restoring-force surface of all records");
  command->add_option("recordings", o->recordings, "recordings (each with its JSON sidecar)")
      ->required();
  command->add_option("--edc", o->edc_path,
                      "EDC table (CSV): well,f0_n,edc_mean_j,edc_std_j,cycles,... per level");
  command->add_option("--rfs", o->rfs_path,
                      "stiffness slice (CSV): z_m,restoring_force_n,samples (|z_dot| small)");
  command->add_option("--damping", o->damping_path,
                      "damping slices at the stable equilibria (CSV): z_center_m,z_dot_m_s,"
                      "damping_force_n,samples");
  command->add_option("--cycles", o->cycles_path, "every fitted cycle (CSV)");
  command->add_option("--summary", o->summary_path,
                      "summary (JSON): settings, detections, stiffness_fit with standard errors");
  command->add_option("--model-out", o->model_out_path,
                      "write the identified model (JSON): the recordings' mass and the stiffness "
                      "slice's K(z), with the friction and damping of --model");
  command
      ->add_option("--model", o->model,
                   "starting friction and damping for --model-out: paper | illustrative | "
                   "MODEL.json")
      ->capture_default_str();
  command
      ->add_option("--freq", o->freq_hz,
                   "excitation frequency [Hz] (default: sidecar, else detected)")
      ->check(positive_number());
  command->add_option("--well", o->well, "well of the records when the mass channel cannot tell")
      ->check(CLI::IsMember({"positive", "negative"}));
  command->add_flag("--timing", o->timing,
                    "print where the time went: reading, analysis, output (steady clock)");
  command->add_flag("--detect-levels", o->detect_levels,
                    "find levels from the force amplitude even when the sidecar lists them");
  command->add_option("--harmonics", o->settings.harmonics, "harmonics per cycle fit")
      ->capture_default_str();
  command
      ->add_option("--highpass", o->settings.integration_highpass_hz,
                   "cut-off of the zero-phase double integration [Hz]")
      ->capture_default_str();
  command
      ->add_option("--lowpass", o->settings.derivative_lowpass_hz,
                   "cut-off of the spectral differentiation [Hz]")
      ->capture_default_str();
  command
      ->add_option("--well-boundary", o->settings.well_boundary_m,
                   "z between the wells [m] (cross-well detection)")
      ->capture_default_str();
  command->callback([o] {
    if (o->edc_path.empty() && o->rfs_path.empty() && o->summary_path.empty() &&
        o->model_out_path.empty()) {
      throw InputError("analyze: nothing to write: give --edc, --rfs, --summary or --model-out");
    }
    run(*o);
  });
}

}  // namespace oscilab::cli
