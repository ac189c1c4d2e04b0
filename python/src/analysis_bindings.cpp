// Measurement analysis (§3, §4.1): the same daq::analyze_recordings / analysis::analyze_campaign
// as `oscilab-cli analyze`, results as tables named like its CSV columns and JSON keys.
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "analysis/common/input_error.h"
#include "analysis/pipeline/cycle_table.h"
#include "analysis/pipeline/edc_table.h"
#include "analysis/pipeline/offline_analysis.h"
#include "bindings.h"
#include "daq/export/mat_export.h"
#include "daq/recording/campaign_reader.h"
#include "daq/recording/measurement_mapping.h"
#include "python_types.h"

namespace oscilab::python {

namespace {

// One column of a table as a NumPy array of its kind's dtype (docs/python.md): float64, int64,
// bool, or unicode (<U…, as wide as the longest text).
template <class Row>
py::array column_array(const analysis::TableColumn<Row>& column, const std::vector<Row>& rows) {
  const auto n = static_cast<py::ssize_t>(rows.size());
  switch (column.kind) {
    case analysis::ColumnKind::Real: {
      py::array_t<double> out(n);
      double* data = out.mutable_data();
      for (py::ssize_t i = 0; i < n; ++i) data[i] = std::get<double>(column.value(rows[i]));
      return out;
    }
    case analysis::ColumnKind::Integer: {
      py::array_t<std::int64_t> out(n);
      std::int64_t* data = out.mutable_data();
      for (py::ssize_t i = 0; i < n; ++i) data[i] = std::get<std::int64_t>(column.value(rows[i]));
      return out;
    }
    case analysis::ColumnKind::Flag: {
      py::array_t<bool> out(n);
      bool* data = out.mutable_data();
      for (py::ssize_t i = 0; i < n; ++i) data[i] = std::get<bool>(column.value(rows[i]));
      return out;
    }
    case analysis::ColumnKind::Text:
      break;
  }
  py::list texts;
  for (const Row& row : rows) texts.append(py::str(std::get<std::string>(column.value(row))));
  return py::module_::import("numpy").attr("array")(texts, py::arg("dtype") = "U");
}

// A table as a dict of columns in `columns`' order (the CSV's), without the column `skip`.
template <class Row>
py::dict table_dict(const std::vector<analysis::TableColumn<Row>>& columns,
                    const std::vector<Row>& rows, const char* skip = nullptr) {
  py::dict table;
  for (const analysis::TableColumn<Row>& column : columns) {
    if (skip != nullptr && std::string_view(column.name) == skip) continue;
    table[column.name] = column_array(column, rows);
  }
  return table;
}

}  // namespace

py::dict level_table(const std::vector<analysis::EdcTableRow>& rows) {
  return table_dict(analysis::edc_table_columns(), rows);
}

py::dict level_table(const std::vector<analysis::LevelResult>& levels) {
  std::vector<analysis::EdcTableRow> rows;
  rows.reserve(levels.size());
  for (const analysis::LevelResult& level : levels) rows.push_back({"", level, level.flags()});
  return table_dict(analysis::edc_table_columns(), rows, "record");
}

py::dict cycle_table(const std::vector<analysis::CycleTableRow>& rows) {
  return table_dict(analysis::cycle_table_columns(), rows);
}

py::dict cycle_table(const std::vector<analysis::CycleFit>& cycles) {
  return table_dict(analysis::cycle_table_columns(), analysis::cycle_table_rows(cycles), "record");
}

std::shared_ptr<const analysis::CampaignAnalysis> run_analysis(const py::object& recordings,
                                                               const AnalysisArguments& a,
                                                               const py::object& progress) {
  daq::MappingOverrides overrides;
  if (!a.freq_hz.is_none()) {
    const double freq = number_argument(a.freq_hz, "freq_hz");
    if (!(std::isfinite(freq) && freq > 0.0)) {
      throw InputError("freq_hz: " + std::to_string(freq) + " is not a positive number");
    }
    overrides.excitation_freq_hz = freq;
  }
  if (!a.well.is_none()) {
    overrides.well_positive =
        well_argument(text_argument(a.well, "well")) == analysis::Well::Positive;
  }
  overrides.ignore_sidecar_levels = a.detect_levels;
  analysis::PipelineSettings settings;
  settings.harmonics = a.harmonics;
  settings.integration_highpass_hz = a.highpass_hz;
  settings.derivative_lowpass_hz = a.lowpass_hz;
  settings.well_boundary_m = a.well_boundary_m;

  // Recordings in memory go through the same mapping and campaign analysis as files.
  std::vector<analysis::MeasurementChannels> in_memory;
  std::vector<std::string> paths;
  const bool single = py::isinstance<daq::Recording>(recordings) || is_path(recordings);
  if (!single && !py::isinstance<py::iterable>(recordings)) {
    throw py::type_error("recordings: expected a path, a Recording or a sequence of them, not " +
                         py::str(py::type::of(recordings).attr("__name__")).cast<std::string>());
  }
  const py::list items =
      single ? py::list(py::make_tuple(recordings)) : py::list(py::iterable(recordings));
  bool any_recording = false;
  for (const auto& item : items) any_recording |= py::isinstance<daq::Recording>(item);
  if (any_recording) {
    for (const auto& item : items) {
      if (py::isinstance<daq::Recording>(item)) {
        in_memory.push_back(
            daq::measurement_channels(item.cast<const daq::Recording&>(), overrides));
      } else {
        daq::Recording read;
        const std::string path = path_string(item);
        {
          py::gil_scoped_release release;
          read = daq::read_recording(path);
        }
        in_memory.push_back(daq::measurement_channels(read, overrides));
      }
    }
  } else {
    paths = path_list(recordings, "recordings");
  }
  if (items.empty()) throw InputError("recordings: no recordings given");

  auto result = std::make_shared<analysis::CampaignAnalysis>();
  run_job(
      [&](const ReportFn& report, const CancelToken& cancel) {
        *result = any_recording ? analysis::analyze_campaign(in_memory, settings,
                                                             fraction_reporter(report), cancel)
                                : daq::analyze_recordings(paths, overrides, settings,
                                                          fraction_reporter(report), cancel);
      },
      progress);
  // A stepped-sine record none of whose levels measures anything is refused, as the CLI does.
  if (result->status == JobStatus::Ok) analysis::require_measured_levels(*result);
  return result;
}

namespace {

const char* status_name(JobStatus status) {
  switch (status) {
    case JobStatus::Ok:
      return "ok";
    case JobStatus::Cancelled:
      return "cancelled";
    case JobStatus::NoConvergence:
      return "no-convergence";
    case JobStatus::NumericalIssue:
      return "numerical-issue";
    case JobStatus::InvalidInput:
      return "invalid-input";
  }
  return "unknown";
}

}  // namespace

std::string job_status_name(JobStatus status) { return status_name(status); }

namespace {

// Analysis: a record's motion signals, the MATLAB export of the EDC table, repr.
void bind_analysis_methods(py::class_<AnalysisHandle>& cls) {
  cls.def(
         "motion",
         [](const AnalysisHandle& h, int record) {
           const auto& records = h.campaign->records;
           if (record < 0 || record >= static_cast<int>(records.size())) {
             throw InputError("record: " + std::to_string(record) + " is not in 0.." +
                              std::to_string(static_cast<int>(records.size()) - 1));
           }
           const analysis::MotionSignals& s = records[static_cast<std::size_t>(record)].motion;
           py::dict d;
           d["t_s"] = to_array(s.t_s);
           d["z_m"] = to_array(s.z_m);
           d["z_dot_m_s"] = to_array(s.z_dot_m_s);
           d["restoring_force_n"] = to_array(s.restoring_force_n);
           d["z_absolute"] = s.z_absolute;
           return d;
         },
         py::arg("record") = 0,
         "The time signals of the restoring surface of one record (§3): t_s [s], z_m [m], "
         "z_dot_m_s [m/s], restoring_force_n [N] R = f − m z̈, and z_absolute (False: z's mean "
         "unknown).")
      .def(
          "export_edc_mat",
          [](const AnalysisHandle& h, const py::object& path) {
            const std::string p = path_string(path);
            py::gil_scoped_release release;
            daq::write_edc_mat(daq::edc_table_rows(*h.campaign), p);
          },
          py::arg("path"),
          "Writes the EDC table as a MATLAB v5 .mat file (`oscilab-cli export --edc-mat`): one "
          "column vector per column of the table (the keys of `edc`): double for numbers, "
          "logical for usable, cell of char for well, record and flags.")
      .def("__repr__", [](const AnalysisHandle& h) {
        std::size_t levels = 0;
        for (const auto& r : h.campaign->records) levels += r.levels.size();
        return "<oscilab.Analysis " + std::to_string(h.campaign->records.size()) + " records, " +
               std::to_string(levels) + " levels>";
      });
}

// analyze(): recordings to an Analysis.
void bind_analyze(py::module_& m) {
  m.def(
      "analyze",
      [](const py::object& recordings, const py::object& freq_hz, const py::object& well,
         bool detect_levels, int harmonics, double highpass_hz, double lowpass_hz,
         double well_boundary_m, const py::object& progress) {
        AnalysisArguments a{freq_hz,     well,       detect_levels,  harmonics,
                            highpass_hz, lowpass_hz, well_boundary_m};
        return AnalysisHandle{run_analysis(recordings, a, progress)};
      },
      py::arg("recordings"), py::kw_only(), py::arg("freq_hz") = py::none(),
      py::arg("well") = py::none(), py::arg("detect_levels") = false, py::arg("harmonics") = 8,
      py::arg("highpass_hz") = 1.0, py::arg("lowpass_hz") = 60.0, py::arg("well_boundary_m") = 0.0,
      py::arg("progress") = py::none(),
      R"doc(Measurement analysis of recordings (`oscilab-cli analyze`): per-level energy dissipated per
cycle of stepped-sine records and the restoring-force surface of all records together.

recordings: a path, a Recording, or a sequence of them (each file with its JSON sidecar).
freq_hz: excitation frequency [Hz] (default: the sidecar's, else detected).
well: 'positive' or 'negative' when the mass channel cannot tell.
detect_levels: find levels from the force amplitude even when the sidecar lists them.
harmonics: harmonics per cycle fit; highpass_hz: cut-off of the zero-phase double integration
[Hz]; lowpass_hz: cut-off of the spectral differentiation [Hz]; well_boundary_m: z between the
wells [m].
progress: callable(info: dict) with info['fraction'] in [0, 1]; return False to cancel.
Returns an Analysis. Ctrl-C stops it (KeyboardInterrupt); the GIL is released while it runs.)doc");
}

}  // namespace

void bind_analysis(py::module_& m) {
  py::class_<AnalysisHandle> cls(m, "Analysis", R"doc(
The offline analysis of one or more recordings (what `oscilab-cli analyze` computes): the EDC of
every stepped-sine level, the restoring-force surface (stiffness slice with its cubic fit, damping
slices), every fitted cycle. Tables are dicts of NumPy arrays named and ordered like the CLI's
CSV columns (float64, int64, bool, unicode: docs/python.md); the summary is the CLI's --summary
JSON as a dict. Pass it to ``fit`` or ``diagnose`` to reuse it.
)doc");
  cls.def_property_readonly(
         "edc",
         [](const AnalysisHandle& h) { return level_table(analysis::edc_table_rows(*h.campaign)); },
         "EDC table, one row per stepped-sine level of each record, records in order: a dict of "
         "NumPy arrays keyed and ordered like the CSV of `analyze --edc` (docs/contracts.md §3): "
         "well, f0_n [N], edc_mean_j [J], edc_std_j [J], cycles, record, edc_noise_floor_j [J], "
         "edc_eq13_mean_j [J], edc_trapz_mean_j [J], z1_abs_m [m], lag_rad [rad], z_mean_m [m], "
         "start_s [s], end_s [s], transient_cycles, period1_change, usable, flags. dtypes: "
         "float64 for reals, int64 for counts (cycles, transient_cycles), bool for usable, "
         "unicode (<U...) for well, record and flags; pandas.DataFrame(a.edc) takes it as it is. "
         "J/kg and N/kg without mass_kg (flag per-unit-mass).")
      .def_property_readonly(
          "cycles",
          [](const AnalysisHandle& h) {
            return cycle_table(analysis::cycle_table_rows(*h.campaign));
          },
          "Every fitted cycle, records in order: a dict of NumPy arrays keyed and ordered like the "
          "CSV of `analyze --cycles`: record (unicode <U...), start_s [s], end_s [s], f0_n [N], "
          "edc_j [J], edc_eq13_j [J], edc_trapz_j [J], z1_abs_m [m], lag_rad [rad], z_mean_m [m], "
          "z_min_m [m], z_max_m [m] (float64).")
      .def_property_readonly(
          "rfs",
          [](const AnalysisHandle& h) -> py::object {
            if (!h.campaign->stiffness) return py::none();
            std::vector<double> z, force;
            std::vector<int> samples;
            for (const auto& bin : h.campaign->stiffness->bins) {
              z.push_back(bin.x);
              force.push_back(bin.force_n);
              samples.push_back(bin.samples);
            }
            py::dict t;
            t["z_m"] = to_array(z);
            t["restoring_force_n"] = to_array(force);
            t["samples"] = to_int_array(samples);
            return t;
          },
          "Stiffness slice (columns of `analyze --rfs`): z_m [m] bin centres, restoring_force_n "
          "[N] R = f − m z̈ at ż ≈ 0, samples per bin; None when no slice could be made "
          "(rfs_message says why).")
      .def_property_readonly(
          "damping",
          [](const AnalysisHandle& h) {
            std::vector<double> center, z_dot, force;
            std::vector<int> samples;
            for (const auto& slice : h.campaign->damping) {
              for (const auto& bin : slice.bins) {
                center.push_back(slice.z_center_m);
                z_dot.push_back(bin.x);
                force.push_back(bin.force_n);
                samples.push_back(bin.samples);
              }
            }
            py::dict t;
            t["z_center_m"] = to_array(center);
            t["z_dot_m_s"] = to_array(z_dot);
            t["damping_force_n"] = to_array(force);
            t["samples"] = to_int_array(samples);
            return t;
          },
          "Damping slices at the stable equilibria (columns of `analyze --damping`): "
          "z_center_m [m], z_dot_m_s [m/s], damping_force_n [N], samples.")
      .def_property_readonly(
          "summary",
          [](const AnalysisHandle& h) {
            return to_python(analysis::campaign_summary(*h.campaign));
          },
          "The summary JSON of `analyze --summary` as a dict: stiffness_fit, settings, records, "
          "damping_slices ...")
      .def_property_readonly(
          "stiffness_fit",
          [](const AnalysisHandle& h) {
            return to_python(analysis::campaign_summary(*h.campaign)["stiffness_fit"]);
          },
          "K(z) = k3 z³ + k2 z² − k1 z + k0 (eq. (2)) fitted to the stiffness slice: keys "
          "k3_n_m3, k2_n_m2, k1_n_m, k0_n, each with a _std twin, and residual_rms_n, samples, "
          "velocity_band_m_s, z_min_m, z_max_m; None when there is no slice.")
      .def_property_readonly(
          "rfs_message", [](const AnalysisHandle& h) { return h.campaign->rfs_message; },
          "Why there is no stiffness slice, when there is none.")
      .def_property_readonly(
          "status", [](const AnalysisHandle& h) { return job_status_name(h.campaign->status); },
          "'ok', or 'cancelled' when the progress callback returned False.")
      .def_property_readonly(
          "records",
          [](const AnalysisHandle& h) {
            py::list out;
            for (const auto& r : h.campaign->records) {
              py::dict d;
              d["name"] = r.name;
              d["stepped_sine"] = r.stepped_sine;
              d["excitation_freq_hz"] = r.setup.excitation_freq_hz;
              d["frequency_detected"] = r.frequency_detected;
              d["per_unit_mass"] = r.per_unit_mass;
              d["levels"] = r.levels.size();
              d["cycles"] = r.cycles.size();
              py::list notes;
              for (const auto& note : r.notes) notes.append(note);
              d["notes"] = notes;
              out.append(d);
            }
            return out;
          },
          "Per record: name, stepped_sine, excitation_freq_hz [Hz], frequency_detected, "
          "per_unit_mass, levels, cycles, notes.");
  bind_analysis_methods(cls);

  bind_analyze(m);
}

}  // namespace oscilab::python
