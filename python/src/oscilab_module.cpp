// The Python module `oscilab._native._oscilab`: the package python/oscilab/ re-exports it. One
// file per concept (recording, analysis, models, simulation, hbm, fit and diagnose, live); this
// one registers them and the error rule.
#include <cctype>
#include <cerrno>
#include <cstring>
#include <initializer_list>
#include <string>
#include <utility>

#include "analysis/common/input_error.h"
#include "bindings.h"

namespace oscilab::python {
namespace {

// The module's exceptions, created at import (PyErr_NewExceptionWithDoc) and kept by the module:
//   Error                         everything the module raises for a reason of its own
//   InputError(Error, ValueError) bad input: a value, a field, a file's content
//   FileError(Error, OSError)     the file system refused a file (cannot open, read, write)
//   MissingFileError(FileError, FileNotFoundError)
// so that `except ValueError`, `except OSError` and `except FileNotFoundError` keep working.
PyObject* error_type = nullptr;
PyObject* input_error_type = nullptr;
PyObject* file_error_type = nullptr;
PyObject* missing_file_error_type = nullptr;

PyObject* new_exception(py::module_& m, const char* name, const char* doc,
                        std::initializer_list<PyObject*> bases) {
  py::tuple base_tuple(bases.size());
  std::size_t i = 0;
  for (PyObject* base : bases) base_tuple[i++] = py::reinterpret_borrow<py::object>(base);
  const std::string qualified = std::string("oscilab.") + name;
  PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, base_tuple.ptr(), nullptr);
  if (!type) throw py::error_already_set();
  m.add_object(name, py::reinterpret_borrow<py::object>(type));  // the module keeps a reference
  return type;
}

// The error rule: InputError is bad input and becomes InputError (a ValueError) with the CLI's
// one-line message (the CLI prints it after "oscilab-cli: "); when that message says the file
// system refused a file (not found, cannot open, read or write it) it becomes FileError (an
// OSError) instead, and MissingFileError (a FileNotFoundError) for a missing file.
bool is_file_problem(const std::string& message) {
  for (const char* marker : {": file not found", ": cannot open",
                             ": cannot read: ", ": cannot write", ": cannot create"}) {
    if (message.find(marker) != std::string::npos) return true;
  }
  return false;
}

bool is_missing_file(const std::string& message) {
  return message.find(": file not found") != std::string::npos ||
         message.find(std::strerror(ENOENT)) != std::string::npos;
}

// The few core messages that name a command-line option name the keyword argument instead:
// "--method: ..." → "method: ...", "--freq" → "freq_hz", "--source" → "source".
std::string with_keyword_names(std::string message) {
  static const std::pair<const char*, const char*> kOptions[] = {
      {"--method", "method"}, {"--stiffness", "stiffness"},   {"--freq", "freq_hz"},
      {"--source", "source"}, {"--model-form", "model_form"}, {"--well", "well"}};
  for (const auto& [option, keyword] : kOptions) {
    const std::string text = option;
    for (std::size_t at = message.find(text); at != std::string::npos;
         at = message.find(text, at)) {
      const std::size_t after = at + text.size();
      const bool whole =
          after == message.size() ||
          !(std::isalnum(static_cast<unsigned char>(message[after])) || message[after] == '-');
      if (!whole) {
        at = after;
        continue;
      }
      message.replace(at, text.size(), keyword);
      at += std::strlen(keyword);
    }
  }
  return message;
}

// pybind11's cast failure names a C++ type and a build flag; say what Python would instead.
std::string cast_message(const std::string& what) {
  std::string text = what;
  const std::size_t hint = text.find(" (#define PYBIND11_DETAILED_ERROR_MESSAGES");
  if (hint != std::string::npos) text.erase(hint);
  return text + " (wrong argument type: see help() of the function for what it takes)";
}

}  // namespace
}  // namespace oscilab::python

PYBIND11_MODULE(_oscilab, m) {
  namespace py = pybind11;
  using namespace oscilab::python;
  m.doc() =
      "Oscilab's C++ core (pybind11). Use the package `oscilab`, which re-exports this module.";
  error_type = new_exception(
      m, "Error",
      "Base of the exceptions oscilab raises: InputError (bad input, also a ValueError), "
      "FileError (a file the system refused, also an OSError) and MissingFileError (also a "
      "FileNotFoundError).",
      {PyExc_Exception});
  input_error_type = new_exception(
      m, "InputError",
      "Bad input: a value, an array, a sidecar field or a file's content, with one message "
      "naming the keyword argument, file, field or value (the CLI's message). A ValueError.",
      {error_type, PyExc_ValueError});
  file_error_type = new_exception(
      m, "FileError", "A file the file system refused (cannot open, read or write). An OSError.",
      {error_type, PyExc_OSError});
  missing_file_error_type = new_exception(
      m, "MissingFileError", "A file that does not exist. A FileError and a FileNotFoundError.",
      {file_error_type, PyExc_FileNotFoundError});
  py::register_local_exception_translator([](std::exception_ptr error) {
    try {
      if (error) std::rethrow_exception(error);
    } catch (const oscilab::InputError& e) {
      const std::string message = with_keyword_names(e.what());
      if (is_missing_file(message)) {
        // errno as for open(): `error.errno == errno.ENOENT` holds; str(error) stays the message.
        const py::object error_object =
            py::reinterpret_borrow<py::object>(missing_file_error_type)(message);
        error_object.attr("errno") = ENOENT;
        PyErr_SetObject(missing_file_error_type, error_object.ptr());
      } else if (is_file_problem(message)) {
        PyErr_SetString(file_error_type, message.c_str());
      } else {
        PyErr_SetString(input_error_type, message.c_str());
      }
    } catch (const py::cast_error& e) {
      PyErr_SetString(PyExc_TypeError, cast_message(e.what()).c_str());
    }
  });
  m.attr("__version__") = OSCILAB_VERSION;  // CMakeLists.txt: project(Oscilab VERSION ...)
  bind_recording(m);
  bind_analysis(m);
  bind_models(m);
  bind_simulation(m);
  bind_hbm(m);
  bind_fit(m);
  bind_design(m);
  bind_live(m);
  bind_bench(m);
}
