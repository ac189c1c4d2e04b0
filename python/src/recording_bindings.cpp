// Recordings: read any format read_recording knows (libsndfile containers, CSV and the readers
// behind daq/recording/format_reader.h), build one from arrays and a sidecar, write it.
#include <cmath>
#include <string>

#include "analysis/common/input_error.h"
#include "analysis/common/json_limits.h"
#include "bindings.h"
#include "daq/export/mat_export.h"
#include "daq/export/uff58_export.h"
#include "daq/recording/format_reader.h"
#include "daq/recording/recording.h"
#include "daq/recording/recording_summary.h"
#include "daq/recording/sidecar.h"
#include "daq/recording/sidecar_draft.h"
#include "daq/recording/stored_samples.h"

namespace oscilab::python {
namespace {

using daq::Recording;

daq::Sidecar sidecar_argument(const py::handle& object) {
  return daq::parse_sidecar(json_argument(object, "sidecar"), "sidecar");
}

Recording make_unchecked_recording(const py::handle& sidecar_object, const py::handle& samples) {
  Recording recording;
  // The samples are SI already: a channel's scale only maps them to stored values when the
  // recording is written, so a channel without one gets 1.
  nlohmann::json sidecar = json_argument(sidecar_object, "sidecar");
  if (sidecar.is_object() && sidecar.contains("channels") && sidecar["channels"].is_array()) {
    for (nlohmann::json& channel : sidecar["channels"]) {
      if (channel.is_object() && !channel.contains("scale")) channel["scale"] = 1.0;
    }
  }
  recording.sidecar = daq::parse_sidecar(sidecar, "sidecar");
  const auto& channels = recording.sidecar.channels;
  const auto n_channels = static_cast<Eigen::Index>(channels.size());
  if (py::isinstance<py::dict>(samples)) {
    const py::dict by_name = samples.cast<py::dict>();
    Eigen::Index rows = -1;
    for (Eigen::Index c = 0; c < n_channels; ++c) {
      const std::string& name = channels[static_cast<std::size_t>(c)].name;
      if (!by_name.contains(name)) {
        throw InputError("samples: no array for the sidecar's channel \"" + name + "\"");
      }
      const Eigen::VectorXd column = to_vector(by_name[py::str(name)], "samples[\"" + name + "\"]");
      if (rows < 0) {
        rows = column.size();
        recording.samples_si.resize(rows, n_channels);
      } else if (column.size() != rows) {
        throw InputError("samples[\"" + name + "\"]: " + std::to_string(column.size()) +
                         " samples, the first channel has " + std::to_string(rows));
      }
      recording.samples_si.col(c) = column;
    }
    if (by_name.size() != channels.size()) {
      throw InputError("samples: " + std::to_string(by_name.size()) + " arrays for " +
                       std::to_string(channels.size()) + " sidecar channels");
    }
    return recording;
  }
  py::array_t<double, py::array::c_style | py::array::forcecast> array;
  try {
    array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(samples);
  } catch (const py::error_already_set&) {
    throw InputError("samples: not an array of numbers");
  }
  if (!array || array.ndim() != 2) {
    throw InputError("samples: must be a 2-D array (samples × channels) or a dict of arrays");
  }
  if (array.shape(1) != n_channels) {
    throw InputError("samples: " + std::to_string(array.shape(1)) + " columns for " +
                     std::to_string(n_channels) + " sidecar channels");
  }
  const auto view = array.unchecked<2>();
  recording.samples_si.resize(array.shape(0), n_channels);
  for (py::ssize_t r = 0; r < array.shape(0); ++r) {
    for (py::ssize_t c = 0; c < n_channels; ++c) recording.samples_si(r, c) = view(r, c);
  }
  return recording;
}

// Samples built in Python are checked as a file's are (daq/recording/stored_samples.cpp): a
// non-finite sample outside the sidecar's invalid intervals is an error naming the channel and
// the first such sample.
void check_finite(const Recording& recording) {
  const daq::Sidecar& sidecar = recording.sidecar;
  const Eigen::MatrixXd& samples = recording.samples_si;
  const daq::StoredSamples no_lines;
  for (Eigen::Index c = 0; c < samples.cols(); ++c) {
    Eigen::Index first_bad = -1;
    Eigen::Index bad_count = 0;
    for (Eigen::Index r = 0; r < samples.rows(); ++r) {
      if (!std::isfinite(samples(r, c)) && !daq::declared_invalid(sidecar, r)) {
        if (first_bad < 0) first_bad = r;
        ++bad_count;
      }
    }
    if (first_bad < 0) continue;
    const double value = samples(first_bad, c);
    throw InputError("samples: channel \"" + sidecar.channels[static_cast<std::size_t>(c)].name +
                     "\": " + daq::sample_place(first_bad, sidecar.sample_rate_hz, no_lines) +
                     (std::isnan(value) ? " is NaN" : " is infinite") + "; " +
                     std::to_string(bad_count) + " of " + std::to_string(samples.rows()) +
                     " samples of this channel are not finite");
  }
}

Recording make_recording(const py::handle& sidecar_object, const py::handle& samples) {
  Recording recording = make_unchecked_recording(sidecar_object, samples);
  check_finite(recording);
  return recording;
}

// A read-only NumPy view of the recording's samples (Eigen stores them column by column: a
// Fortran-order array), kept alive by the Recording object `owner`: no copy on every access, and
// a write raises instead of changing a copy.
py::array_t<double> read_only_view(const Eigen::MatrixXd& samples, const py::handle& owner) {
  const auto rows = static_cast<py::ssize_t>(samples.rows());
  const auto cols = static_cast<py::ssize_t>(samples.cols());
  const auto item = static_cast<py::ssize_t>(sizeof(double));
  py::array_t<double> view({rows, cols}, {item, item * rows}, samples.data(), owner);
  view.attr("setflags")(py::arg("write") = false);
  return view;
}

// One channel (a column, contiguous) as a read-only view.
py::array_t<double> read_only_column(const Recording& r, int index, const py::handle& owner) {
  const auto rows = static_cast<py::ssize_t>(r.samples_si.rows());
  py::array_t<double> view({rows}, {static_cast<py::ssize_t>(sizeof(double))},
                           r.samples_si.col(index).data(), owner);
  view.attr("setflags")(py::arg("write") = false);
  return view;
}

// Equal samples: element by element, NaN equal to NaN (declared invalid samples are NaN).
bool same_samples(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) return false;
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    const double x = a.data()[i];
    const double y = b.data()[i];
    if (!(x == y || (std::isnan(x) && std::isnan(y)))) return false;
  }
  return true;
}

Eigen::MatrixXd matrix_of(const py::handle& object) {
  const auto array = py::array_t<double, py::array::f_style | py::array::forcecast>::ensure(object);
  if (!array || array.ndim() != 2) throw InputError("Recording state: samples must be 2-D");
  return Eigen::Map<const Eigen::MatrixXd>(array.data(), array.shape(0), array.shape(1));
}

daq::ChannelRole parse_role(const std::string& role) {
  for (daq::ChannelRole r : {daq::ChannelRole::Base, daq::ChannelRole::Mass,
                             daq::ChannelRole::Relative, daq::ChannelRole::Force}) {
    if (daq::to_string(r) == role) return r;
  }
  throw InputError("role: unknown role \"" + role + "\" (base, mass, relative, force)");
}

// Recording: its channels by name, conversions, writing, description, pickling and repr.
void bind_recording_methods(py::class_<Recording>& cls) {
  cls.def(
         "channel",
         [](const py::object& self, const std::string& name) {
           const Recording& r = self.cast<const Recording&>();
           const int index = r.channel_index(name);
           if (index < 0) throw InputError("channel: no channel named \"" + name + "\"");
           return read_only_column(r, index, self);
         },
         py::arg("name"),
         "The SI samples of the channel named `name` (1-D array, a read-only view).")
      .def(
          "channel_by_role",
          [](const py::object& self, const std::string& role) {
            const Recording& r = self.cast<const Recording&>();
            const int index = r.channel_index(parse_role(role));
            if (index < 0)
              throw InputError("channel_by_role: no channel with role \"" + role + "\"");
            return read_only_column(r, index, self);
          },
          py::arg("role"),
          "The SI samples of the first channel with `role` (base, mass, relative, force).")
      .def(
          "__getitem__",
          [](const py::object& self, const std::string& name) {
            const Recording& r = self.cast<const Recording&>();
            const int index = r.channel_index(name);
            if (index < 0) throw py::key_error(name);
            return read_only_column(r, index, self);
          },
          py::arg("name"), "recording['y']: the SI samples of channel 'y'.")
      .def(
          "write",
          [](const Recording& r, const py::object& path) {
            const std::string p = path_string(path);
            py::gil_scoped_release release;
            daq::write_recording(r, p);
          },
          py::arg("path"),
          "Writes samples and sidecar (same stem, .json); the container follows the extension "
          "(.wav .flac .w64 .rf64 .aiff .caf .csv). Same as write_recording(recording, path).")
      .def(
          "export_mat",
          [](const Recording& r, const py::object& path) {
            const std::string p = path_string(path);
            py::gil_scoped_release release;
            daq::write_recording_mat(r, p);
          },
          py::arg("path"),
          "Writes the recording as a MATLAB v5 .mat file (`oscilab-cli export --mat`): t_s, one "
          "variable per channel in SI, sample_rate_hz, mass_kg, sidecar_json, channel_names, "
          "channel_variables, channel_units; NaN gaps kept.")
      .def(
          "export_uff",
          [](const Recording& r, const py::object& path, int base_node, int mass_node,
             int direction) {
            daq::Uff58Options options;
            options.base_node = base_node;
            options.mass_node = mass_node;
            options.direction = direction;
            const std::string p = path_string(path);
            py::gil_scoped_release release;
            daq::write_recording_uff58(r, p, options);
          },
          py::arg("path"), py::kw_only(), py::arg("base_node") = 1, py::arg("mass_node") = 2,
          py::arg("direction") = 1,
          "Writes the recording as a Universal File (`oscilab-cli export --uff`): a dataset 164 "
          "(SI) and one dataset 58 per channel. base_node: the table's node (base channels); "
          "mass_node: the mass's (mass, relative, force); direction: 1..6 (±X, ±Y, ±Z, "
          "rotation), 0 scalar. UFF has no missing value: a non-finite sample is an InputError.")
      .def("describe", &daq::describe_recording,
           "What the recording holds, as text: the output of `oscilab-cli info`.")
      .def(
          "__eq__",
          [](const Recording& a, const py::object& other) -> py::object {
            if (!py::isinstance<Recording>(other))
              return py::reinterpret_borrow<py::object>(Py_NotImplemented);
            const Recording& b = other.cast<const Recording&>();
            return py::bool_(daq::sidecar_to_json(a.sidecar) == daq::sidecar_to_json(b.sidecar) &&
                             same_samples(a.samples_si, b.samples_si));
          },
          py::arg("other"),
          "Equal recordings: the same sidecar and the same SI samples (NaN equal to NaN); where "
          "they were read from does not matter.")
      .def(py::pickle(
          [](const Recording& r) {
            // State: the sidecar as JSON text, the SI and stored samples, where it came from.
            return py::make_tuple(daq::sidecar_to_json(r.sidecar).dump(), to_array(r.samples_si),
                                  r.samples_stored.size() == 0
                                      ? py::object(py::none())
                                      : py::object(to_array(r.samples_stored)),
                                  r.source_path, r.container);
          },
          [](const py::tuple& state) {
            if (state.size() != 5) throw InputError("Recording state: expected 5 items");
            Recording r;
            r.sidecar = daq::parse_sidecar(
                parse_json_within_limits(state[0].cast<std::string>(), "Recording state"),
                "sidecar");
            r.samples_si = matrix_of(state[1]);
            if (!state[2].is_none()) r.samples_stored = matrix_of(state[2]);
            r.source_path = state[3].cast<std::string>();
            r.container = state[4].cast<std::string>();
            return r;
          }))
      .def("__repr__", [](const Recording& r) {
        return "<oscilab.Recording " + std::to_string(r.samples_si.cols()) + " channels, " +
               std::to_string(r.sample_count()) + " samples at " +
               std::to_string(r.sidecar.sample_rate_hz) + " Hz" +
               (r.source_path.empty() ? std::string() : ", " + r.source_path) + ">";
      });
}

// read_recording(), write_recording(), draft_sidecar() and describe_recording(): recordings as
// files.
void bind_recording_files(py::module_& m) {
  m.def(
      "read_recording",
      [](const py::object& path, const py::object& sidecar) {
        const std::string p = path_string(path);
        if (sidecar.is_none()) {
          py::gil_scoped_release release;
          return daq::read_recording(p);
        }
        const daq::Sidecar given = sidecar_argument(sidecar);
        py::gil_scoped_release release;
        return daq::read_recording(p, given);
      },
      py::arg("path"), py::arg("sidecar") = py::none(),
      R"doc(Reads a recording with its JSON sidecar of the same stem: any container the core reads
(WAV, FLAC, W64, RF64, AIFF, CAF, CSV, and the other formats behind its readers). With
``sidecar`` (a dict), that sidecar describes the file instead of the one beside it. Samples come
back in SI units (calibration and unit conversion applied).

``path``: str, bytes or os.PathLike. Raises MissingFileError (a FileNotFoundError) when the file
does not exist, FileError (an OSError) when it cannot be opened, InputError (a ValueError) with
the reader's one-line message (the CLI's) for anything it cannot trust.)doc");
  m.def(
      "write_recording",
      [](const Recording& recording, const py::object& path) {
        const std::string p = path_string(path);
        py::gil_scoped_release release;
        daq::write_recording(recording, p);
      },
      py::arg("recording"), py::arg("path"),
      "Writes a recording and its sidecar (same stem, .json); the container follows the "
      "extension. Both files are renamed into place, so a failure leaves no half-written "
      "recording. Raises FileError (an OSError) when the file cannot be written.");
  m.def(
      "draft_sidecar",
      [](const py::object& path) {
        const std::string p = path_string(path);
        daq::SidecarDraft draft;
        {
          py::gil_scoped_release release;
          draft = daq::draft_sidecar(daq::format_for_file(p).describe(p));
        }
        py::dict out;
        // json.loads keeps the draft's key order (the sidecar's), which a JSON object would sort.
        out["sidecar"] = py::module_::import("json").attr("loads")(draft.sidecar.dump());
        out["notes"] = py::cast(draft.notes);
        out["complete"] = draft.complete;
        return out;
      },
      py::arg("path"),
      R"doc(A sidecar drafted from what a file holds (`oscilab-cli info FILE --draft-sidecar`), for
a file another program wrote (TDMS, UFF 58, MATLAB, HDF5, a sound file ...) to check and complete.

Returns a dict: sidecar (the draft, a dict in the sidecar's key order: write it beside the file
as STEM.json, or pass it to read_recording(path, sidecar=...)), notes (what was guessed and what
is missing, one line each), complete (True when every required field has a value).)doc");
  m.def(
      "describe_recording",
      [](const py::object& path) {
        const std::string p = path_string(path);
        py::gil_scoped_release release;
        return daq::describe_recording(daq::read_recording(p));
      },
      py::arg("path"),
      "The text `oscilab-cli info PATH` prints: channels, units, rate, "
      "duration, excitation.");
}

}  // namespace

void bind_recording(py::module_& m) {
  py::class_<Recording> cls(m, "Recording", R"doc(
A recording in memory: the sidecar (contract §1) and the samples in SI units (m/s², m/s, m, N),
one column per sidecar channel, one row per sample at ``sample_rate_hz``.

``Recording(sidecar, samples)`` builds one: ``sidecar`` is a dict (or JSON text) in the sidecar
format of docs/contracts.md §1 (``sample_rate_hz``, ``mass_kg``, ``channels`` with ``name``,
``role``, ``quantity``, ``unit``, ``scale`` ...), ``samples`` a 2-D array (samples × channels) in
SI or a dict channel name → 1-D array; a channel without ``scale`` gets 1. Stored value =
(SI / unit factor − offset) / scale when written. Raises InputError (a ValueError) with the
reader's message for an invalid sidecar, and for a NaN or infinite sample outside the sidecar's
``invalid_intervals`` (naming the channel and the first such sample), as the readers do.

Recordings pickle, and compare equal when their sidecars and SI samples are.
)doc");
  cls.def(py::init([](const py::object& sidecar, const py::object& samples) {
            return make_recording(sidecar, samples);
          }),
          py::arg("sidecar"), py::arg("samples"))
      .def_property(
          "sidecar", [](const Recording& r) { return to_python(daq::sidecar_to_json(r.sidecar)); },
          [](Recording& r, const py::object& sidecar) {
            daq::Sidecar parsed = sidecar_argument(sidecar);
            if (parsed.channels.size() != static_cast<std::size_t>(r.samples_si.cols())) {
              throw InputError("sidecar: " + std::to_string(parsed.channels.size()) +
                               " channels for " + std::to_string(r.samples_si.cols()) +
                               " sample columns");
            }
            r.sidecar = std::move(parsed);
          },
          "The sidecar as a dict (contract §1 keys); assign a dict to replace it.")
      .def_property_readonly(
          "sample_rate_hz", [](const Recording& r) { return r.sidecar.sample_rate_hz; },
          "Sample rate [Hz].")
      .def_property_readonly(
          "mass_kg",
          [](const Recording& r) -> py::object {
            return r.sidecar.mass_kg ? py::object(py::float_(*r.sidecar.mass_kg))
                                     : py::object(py::none());
          },
          "Mass of the oscillator [kg], or None when the sidecar does not give it.")
      .def_property_readonly(
          "channel_names",
          [](const Recording& r) {
            py::list names;
            for (const auto& c : r.sidecar.channels) names.append(c.name);
            return names;
          },
          "Channel names in column order.")
      .def_property_readonly(
          "channels",
          [](const Recording& r) { return to_python(daq::sidecar_to_json(r.sidecar)["channels"]); },
          "The sidecar's channel descriptions (list of dicts: name, role, quantity, unit, scale, "
          "offset, sensor ...).")
      .def_property_readonly(
          "samples",
          [](const py::object& self) {
            return read_only_view(self.cast<const Recording&>().samples_si, self);
          },
          "Samples in SI units, 2-D array (samples × channels): a read-only view of the "
          "recording's own samples (no copy; np.array(rec.samples) makes a writable copy).")
      .def_property_readonly(
          "samples_stored",
          [](const Recording& r) -> py::object {
            if (r.samples_stored.size() == 0) return py::none();
            return to_array(r.samples_stored);
          },
          "The values exactly as the file stores them (before calibration), or None for a "
          "recording made in memory.")
      .def_property_readonly(
          "t_s",
          [](const Recording& r) {
            Eigen::VectorXd t(r.sample_count());
            for (Eigen::Index i = 0; i < t.size(); ++i) {
              t[i] = static_cast<double>(i) / r.sidecar.sample_rate_hz;
            }
            return to_array(t);
          },
          "Sample times t = i / sample_rate_hz [s].")
      .def_property_readonly(
          "source_path", [](const Recording& r) { return r.source_path; },
          "Where it was read from ('' when made in memory).")
      .def_property_readonly(
          "container", [](const Recording& r) { return r.container; },
          "The file's container as the reader saw it, e.g. 'FLAC ...' or 'CSV'.")
      .def_property_readonly("duration_s", &Recording::duration_s, "Duration [s].")
      .def_property_readonly("sample_count", &Recording::sample_count, "Samples per channel.");
  bind_recording_methods(cls);

  bind_recording_files(m);
}

}  // namespace oscilab::python
