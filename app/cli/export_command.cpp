// oscilab-cli export REC... [--mat OUT.mat] [--uff OUT.uff] [--edc-mat EDC.mat]: recordings as
// MATLAB v5 files and Universal Files (dataset 58), the EDC table as a MATLAB file.
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analysis/common/input_error.h"
#include "analysis/edc/well.h"
#include "analysis/pipeline/offline_analysis.h"
#include "app/cli/campaign_input.h"
#include "app/cli/commands.h"
#include "app/cli/option_parsing.h"
#include "daq/export/mat_export.h"
#include "daq/export/uff58_export.h"
#include "daq/recording/recording.h"

namespace oscilab::cli {
namespace {

namespace fs = std::filesystem;

struct ExportOptions {
  std::vector<std::string> recordings;
  std::string mat_path;
  std::string uff_path;
  std::string edc_mat_path;
  double freq_hz = 0.0;
  std::string well;
  daq::Uff58Options uff;
};

std::string lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

bool is_directory_target(const std::string& path) {
  return (!path.empty() && path.back() == '/') || fs::is_directory(path);
}

// Checks the extension of a file target: `option PATH: expected a .mat file`.
void check_extension(const std::string& option, const std::string& path,
                     const std::vector<std::string>& extensions) {
  const std::string extension = lower(fs::path(path).extension().string());
  if (std::find(extensions.begin(), extensions.end(), extension) != extensions.end()) return;
  std::string expected;
  for (const auto& e : extensions) expected += (expected.empty() ? "" : " or ") + e;
  throw InputError(option + " " + path + ": expected a " + expected + " file");
}

// The file each recording is exported to. One recording: `out` itself, or DIR/STEM.EXT when
// `out` is a directory. Several: `out` must be a directory (existing, or ending in '/', then
// created by create_parent_directories), and the recordings' stems must differ.
std::vector<std::string> output_paths(const std::string& option, const std::string& out,
                                      const std::vector<std::string>& recordings,
                                      const std::vector<std::string>& extensions) {
  if (!is_directory_target(out)) {
    if (recordings.size() > 1) {
      throw InputError(option + " " + out + ": " + std::to_string(recordings.size()) +
                       " recordings need a directory (an existing one, or a path ending in '/')");
    }
    check_extension(option, out, extensions);
    return {out};
  }
  std::vector<std::string> paths;
  std::map<std::string, std::string> by_stem;
  for (const auto& recording : recordings) {
    const std::string stem = fs::path(recording).stem().string();
    const auto [it, inserted] = by_stem.emplace(stem, recording);
    if (!inserted) {
      throw InputError(option + " " + out + ": " + it->second + " and " + recording +
                       " would both be written to " + stem + extensions.front());
    }
    paths.push_back((fs::path(out) / (stem + extensions.front())).string());
  }
  return paths;
}

// Creates the directory an output file goes in (`--mat DIR/` for several recordings).
void create_parent_directory(const std::string& option, const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  if (parent.empty() || fs::is_directory(parent)) return;
  std::error_code error;
  fs::create_directories(parent, error);
  if (error) {
    throw InputError(option + " " + parent.string() +
                     ": cannot create directory: " + error.message());
  }
}

void run(const ExportOptions& o) {
  // Every output path and every recording is checked before the first file is written.
  std::vector<std::string> mat_paths;
  std::vector<std::string> uff_paths;
  if (!o.mat_path.empty()) mat_paths = output_paths("--mat", o.mat_path, o.recordings, {".mat"});
  if (!o.uff_path.empty()) {
    uff_paths = output_paths("--uff", o.uff_path, o.recordings, {".uff", ".unv"});
  }
  if (!o.edc_mat_path.empty()) check_extension("--edc-mat", o.edc_mat_path, {".mat"});
  std::vector<daq::Recording> recordings;
  if (!mat_paths.empty() || !uff_paths.empty()) {
    for (const auto& path : o.recordings) recordings.push_back(daq::read_recording(path));
  }
  if (is_directory_target(o.mat_path)) create_parent_directory("--mat", mat_paths.front());
  if (is_directory_target(o.uff_path)) create_parent_directory("--uff", uff_paths.front());
  for (std::size_t i = 0; i < recordings.size(); ++i) {
    const daq::Recording& recording = recordings[i];
    const std::string shape = std::to_string(recording.sidecar.channels.size()) + " channels, " +
                              std::to_string(recording.sample_count()) + " samples";
    if (!mat_paths.empty()) {
      daq::write_recording_mat(recording, mat_paths[i]);
      std::cout << "wrote " << mat_paths[i] << " (" << shape << ", variables t_s";
      for (const auto& name : daq::mat_channel_variables(recording.sidecar)) {
        std::cout << ", " << name;
      }
      std::cout << ")\n";
    }
    if (!uff_paths.empty()) {
      daq::write_recording_uff58(recording, uff_paths[i], o.uff);
      std::cout << "wrote " << uff_paths[i] << " (" << shape
                << ": one UFF dataset 58 per channel)\n";
    }
  }
  if (!o.edc_mat_path.empty()) {
    daq::MappingOverrides overrides;
    if (o.freq_hz > 0) overrides.excitation_freq_hz = o.freq_hz;
    if (!o.well.empty()) {
      overrides.well_positive = analysis::well_from_string(o.well) == analysis::Well::Positive;
    }
    const analysis::CampaignAnalysis campaign =
        run_input_stage(o.recordings, overrides, analysis::PipelineSettings{});
    // A stepped-sine record none of whose levels measures anything is refused, as by analyze.
    analysis::require_measured_levels(campaign);
    const std::vector<daq::EdcTableRow> rows = daq::edc_table_rows(campaign);
    daq::write_edc_mat(rows, o.edc_mat_path);
    std::cout << "wrote " << o.edc_mat_path << " (" << rows.size() << " EDC levels)\n";
  }
  std::cout << std::flush;
}

}  // namespace

void add_export_command(CLI::App& app) {
  auto o = std::make_shared<ExportOptions>();
  CLI::App* command = app.add_subcommand(
      "export",
      "Export recordings to MATLAB (.mat, v5) and Universal File Format (dataset 58) files, and "
      "the EDC table of stepped-sine recordings to MATLAB");
  command->add_option("recordings", o->recordings, "recordings (each with its JSON sidecar)")
      ->required();
  command->add_option("--mat", o->mat_path,
                      "MATLAB v5 file: t_s, one SI column per channel, sample_rate_hz, mass_kg, "
                      "sidecar_json (a directory for several recordings)");
  command->add_option("--uff", o->uff_path,
                      "Universal File (.uff/.unv): dataset 164 (SI) and one dataset 58 time "
                      "response per channel (a directory for several recordings)");
  command->add_option("--edc-mat", o->edc_mat_path,
                      "EDC table of all recordings (MATLAB v5): well, f0_n, edc_mean_j, "
                      "edc_std_j, cycles, ... one row per level");
  command
      ->add_option("--freq", o->freq_hz,
                   "--edc-mat: excitation frequency [Hz] (default: sidecar, else detected)")
      ->check(positive_number());
  command->add_option("--well", o->well,
                      "--edc-mat: well when the mass channel cannot tell: positive or negative");
  command
      ->add_option("--uff-direction", o->uff.direction,
                   "UFF response direction (1, 2, 3: +X, +Y, +Z translation; negative: -)")
      ->capture_default_str();
  command->callback([o] {
    if (o->mat_path.empty() && o->uff_path.empty() && o->edc_mat_path.empty()) {
      throw InputError("export: nothing to write: give --mat, --uff or --edc-mat");
    }
    const std::optional<analysis::Well> well = analysis::parse_well(o->well);
    if (!o->well.empty() && well != analysis::Well::Positive && well != analysis::Well::Negative) {
      throw InputError("--well " + o->well + ": expected positive or negative");
    }
    if (o->uff.direction < -6 || o->uff.direction > 6) {
      throw InputError("--uff-direction " + std::to_string(o->uff.direction) +
                       ": expected a UFF direction from -6 to 6");
    }
    run(*o);
  });
}

}  // namespace oscilab::cli
