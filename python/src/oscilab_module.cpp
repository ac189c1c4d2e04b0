// The Python module `oscilab._native._oscilab`: the package python/oscilab/ re-exports it. One
// file per concept (recording, analysis, models, simulation, hbm, fit and diagnose, live); this
// one registers them and the error rule.
#include <cstring>
#include <string>

#include "analysis/common/input_error.h"
#include "bindings.h"

namespace oscilab::python {
namespace {

// The error rule: InputError is bad input and becomes ValueError with the CLI's one-line message
// (the CLI prints it after "oscilab-cli: "); when that message says the file system refused a
// file (not found, cannot open, read or write it) it becomes OSError instead, and
// FileNotFoundError for a missing file.
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

}  // namespace
}  // namespace oscilab::python

PYBIND11_MODULE(_oscilab, m) {
  namespace py = pybind11;
  using namespace oscilab::python;
  m.doc() =
      "Oscilab's C++ core (pybind11). Use the package `oscilab`, which re-exports this module.";
  py::register_exception_translator([](std::exception_ptr error) {
    try {
      if (error) std::rethrow_exception(error);
    } catch (const oscilab::InputError& e) {
      const std::string message = e.what();
      if (is_missing_file(message)) {
        PyErr_SetString(PyExc_FileNotFoundError, message.c_str());
      } else if (is_file_problem(message)) {
        PyErr_SetString(PyExc_OSError, message.c_str());
      } else {
        PyErr_SetString(PyExc_ValueError, message.c_str());
      }
    }
  });
  m.attr("__version__") = OSCILAB_VERSION;  // CMakeLists.txt: project(Oscilab VERSION ...)
  bind_recording(m);
  bind_analysis(m);
  bind_models(m);
  bind_simulation(m);
  bind_hbm(m);
  bind_fit(m);
  bind_live(m);
  bind_bench(m);
}
