// Models of eq. (1): the paper's (eq. (7), Tables 1 and 3), the illustrative (eq. (14), Table 2),
// from and to the project's model JSON, built from terms; equilibria and eq. (4) frequencies.
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "analysis/common/input_error.h"
#include "analysis/common/json_limits.h"
#include "analysis/model/model.h"
#include "analysis/model/model_json.h"
#include "analysis/model/reference_models.h"
#include "bindings.h"

namespace oscilab::python {
namespace {

using analysis::Model;

// A model file that does not exist is a missing file (MissingFileError, a FileNotFoundError),
// before the core's "cannot open": `what` says which argument named it and what it could be.
std::string existing_model_file(const py::handle& path, const std::string& what) {
  const std::string text = path_string(path);
  if (!std::filesystem::exists(text)) throw InputError(text + ": file not found (" + what + ")");
  return text;
}

// 'paper', 'illustrative' or a model JSON path, as the CLI's --model.
Model model_from_spec_argument(const py::handle& spec, const std::string& where) {
  const std::string text = path_string(spec);
  if (text == "paper" || text == "illustrative") return analysis::model_from_spec(text);
  return analysis::load_model(
      existing_model_file(spec, where + ": not 'paper', 'illustrative' or a model JSON file"));
}

// Evaluates f at every element of a number or an array of numbers (broadcasting a single value
// against an array); a number in gives a float out.
py::object elementwise(const py::object& a, const py::object& b,
                       const std::function<double(double, double)>& f) {
  const auto as_array = [](const py::object& o, const char* name) {
    try {
      return py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(o);
    } catch (const py::error_already_set&) {
      throw InputError(std::string(name) + ": not a number or an array of numbers");
    }
  };
  const auto x = as_array(a, "z_m");
  const auto y = as_array(b, "z_dot_m_s");
  if (!x || !y || x.ndim() > 1 || y.ndim() > 1) {
    throw InputError("z_m, z_dot_m_s: numbers or 1-D arrays of numbers");
  }
  const py::ssize_t nx = x.size(), ny = y.size();
  if (nx != ny && nx != 1 && ny != 1) {
    throw InputError("z_m, z_dot_m_s: arrays of different lengths (" + std::to_string(nx) + ", " +
                     std::to_string(ny) + ")");
  }
  const py::ssize_t n = std::max(nx, ny);
  if (x.ndim() == 0 && y.ndim() == 0) return py::float_(f(*x.data(), *y.data()));
  py::array_t<double> out(n);
  double* o = out.mutable_data();
  for (py::ssize_t i = 0; i < n; ++i) {
    o[i] = f(x.data()[nx == 1 ? 0 : i], y.data()[ny == 1 ? 0 : i]);
  }
  return out;
}

Model model_from_terms(double mass_kg, const py::list& terms, const std::string& name) {
  std::vector<std::unique_ptr<analysis::ModelTerm>> built;
  for (std::size_t i = 0; i < terms.size(); ++i) {
    const std::string where = "terms[" + std::to_string(i) + "]";
    built.push_back(analysis::term_from_json(json_argument(terms[i], where), where));
  }
  return Model(mass_kg, std::move(built), name);
}

}  // namespace

Model model_argument(const py::handle& object) {
  if (py::isinstance<Model>(object)) return object.cast<const Model&>();
  if (py::isinstance<py::dict>(object)) {
    return analysis::model_from_json(json_argument(object, "model"), "model");
  }
  if (is_path(object)) return model_from_spec_argument(object, "model");
  throw InputError("model: expected a Model, a model dict, 'paper', 'illustrative' or a path");
}

namespace {

// Model: what it is made of and its equilibria, forces and potential; pickling and repr.
void bind_model_queries(py::class_<Model>& cls) {
  cls.def_property_readonly(
         "terms",
         [](const Model& model) {
           py::list terms;
           for (const auto& t : model.terms()) terms.append(to_python(t->to_json()));
           return terms;
         },
         "The terms as dicts ({type, parameters...}, SI units in the key names).")
      .def(
          "summary", [](const Model& model) { return to_python(analysis::model_summary(model)); },
          "The model summary of `oscilab-cli model ... --summary` (contract §3): name, mass_kg, "
          "equilibria [{z_m, stable, linear_frequency_hz}] in increasing z, terms.")
      .def(
          "equilibria",
          [](const Model& model) {
            py::list out;
            for (const analysis::Equilibrium& e : model.equilibria()) {
              py::dict d;
              d["z_m"] = e.z_m;
              d["stable"] = e.stable;
              d["linear_frequency_hz"] =
                  e.stable ? py::object(py::float_(e.linear_frequency_hz)) : py::none();
              d["stiffness_n_m"] = e.stiffness_n_m;
              out.append(d);
            }
            return out;
          },
          "The static equilibria K(z*) = 0 in increasing z: z_m [m], stable, "
          "linear_frequency_hz [Hz] of the linearised undamped motion (eq. (4), None when "
          "unstable), stiffness_n_m [N/m] U''(z*).")
      .def(
          "well",
          [](const Model& model, const std::string& well) {
            const analysis::Equilibrium e =
                model.well(well_argument(well) == analysis::Well::Positive);
            py::dict d;
            d["z_m"] = e.z_m;
            d["stable"] = e.stable;
            d["linear_frequency_hz"] = e.linear_frequency_hz;
            d["stiffness_n_m"] = e.stiffness_n_m;
            return d;
          },
          py::arg("well") = "positive",
          "The stable equilibrium z₊* ('positive') or z₋* ('negative') with its eq. (4) "
          "frequency [Hz].")
      .def(
          "restoring_force",
          [](const Model& model, const py::object& z, const py::object& z_dot) {
            return elementwise(z, z_dot, [&model](double zz, double v) {
              const std::vector<double> state = model.initial_state(zz);
              return model.restoring_force(zz, v, state.empty() ? nullptr : state.data());
            });
          },
          py::arg("z_m"), py::arg("z_dot_m_s"),
          "R(z, ż) = Σ F_i [N] of eq. (1) (internal states at rest at z), element-wise over "
          "numbers or arrays.")
      .def(
          "elastic_force",
          [](const Model& model, const py::object& z) {
            return elementwise(z, py::float_(0.0),
                               [&model](double zz, double) { return model.elastic_force(zz); });
          },
          py::arg("z_m"), "K(z) [N], the elastic part of R, element-wise.")
      .def(
          "potential_j",
          [](const Model& model, const py::object& z) {
            return elementwise(z, py::float_(0.0),
                               [&model](double zz, double) { return model.potential_j(zz); });
          },
          py::arg("z_m"), "U(z) [J] of eq. (3), element-wise.")
      .def(
          "__eq__",
          [](const Model& a, const py::object& other) -> py::object {
            if (!py::isinstance<Model>(other))
              return py::reinterpret_borrow<py::object>(Py_NotImplemented);
            return py::bool_(a.to_json() == other.cast<const Model&>().to_json());
          },
          py::arg("other"), "Equal models: the same model JSON (mass, terms, coefficients, name).")
      .def(py::pickle([](const Model& model) { return py::make_tuple(model.to_json().dump()); },
                      [](const py::tuple& state) {
                        if (state.size() != 1) throw InputError("Model state: expected 1 item");
                        return analysis::model_from_json(
                            parse_json_within_limits(state[0].cast<std::string>(), "Model state"),
                            "model");
                      }))
      .def("__repr__", [](const Model& model) {
        return "<oscilab.Model " + model.name() + ", m = " + std::to_string(model.mass_kg()) +
               " kg, " + std::to_string(model.terms().size()) + " terms>";
      });
}

}  // namespace

void bind_models(py::module_& m) {
  py::class_<Model> cls(m, "Model", R"doc(
A single-degree-of-freedom model of eq. (1), m z̈ + Σ F_i(z, ż, s_i) = f(t): a mass [kg] and a
list of named terms (polynomial stiffness, position-dependent friction, viscous damping, ...).

``Model(mass_kg, terms, name='')`` builds one from term dicts in the model JSON's form, e.g.
``{"type": "viscous-damping", "c_ns_m": 2.0}``; ``Model.paper()``, ``Model.illustrative()``,
``Model.from_json(...)``, ``Model.load(path)`` and ``Model.from_spec('paper'|'illustrative'|path)``
make the others. Raises InputError (a ValueError) naming the term and field for bad input.
Models pickle, and compare equal when their model JSON is.
)doc");
  cls.def(py::init([](double mass_kg, const py::list& terms, const std::string& name) {
            return model_from_terms(mass_kg, terms, name);
          }),
          py::arg("mass_kg"), py::arg("terms"), py::arg("name") = "")
      .def_static(
          "paper",
          [](const py::object& fd_zminus_n, const py::object& fd_zero_n,
             const py::object& fd_zplus_n, const py::object& ks, const py::object& c_ns_m,
             const py::object& vt_m_s) {
            const py::object given[] = {fd_zminus_n, fd_zero_n, fd_zplus_n, ks, c_ns_m, vt_m_s};
            bool any = false;
            for (const auto& g : given) any |= !g.is_none();
            if (!any) return analysis::paper_model();
            analysis::PaperFriction f;
            double* fields[] = {&f.fd_zminus_n, &f.fd_zero_n, &f.fd_zplus_n,
                                &f.ks,          &f.c_ns_m,    &f.vt_m_s};
            const char* names[] = {"fd_zminus_n", "fd_zero_n", "fd_zplus_n",
                                   "ks",          "c_ns_m",    "vt_m_s"};
            for (int i = 0; i < 6; ++i) {
              if (!given[i].is_none()) *fields[i] = number_argument(given[i], names[i]);
            }
            return analysis::paper_model(f);
          },
          py::kw_only(), py::arg("fd_zminus_n") = py::none(), py::arg("fd_zero_n") = py::none(),
          py::arg("fd_zplus_n") = py::none(), py::arg("ks") = py::none(),
          py::arg("c_ns_m") = py::none(), py::arg("vt_m_s") = py::none(),
          "The paper's model, eq. (7): Table 1 stiffness, m = 0.26 kg, Table 3 friction. Give "
          "any of θ of eq. (9) (fd_zminus_n, fd_zero_n, fd_zplus_n [N], ks [-], c_ns_m [N s/m], "
          "vt_m_s [m/s]) to replace Table 3's value.")
      .def_static("illustrative", &analysis::illustrative_model,
                  "The illustrative linear oscillator with friction of eq. (14), Table 2: "
                  "m = 1.3 kg, k = 800 N/m, c = 1 N s/m, f_d = 1 N, k_s = 1.2, v_t = 1e-2 m/s.")
      .def_static(
          "from_json",
          [](const py::object& json) {
            return analysis::model_from_json(json_argument(json, "model"), "model");
          },
          py::arg("json"), "A model from its JSON (a dict or JSON text, format oscilab-model/1).")
      .def_static(
          "load",
          [](const py::object& path) {
            return analysis::load_model(existing_model_file(path, "path: a model JSON file"));
          },
          py::arg("path"),
          "Reads a model JSON file (MissingFileError, a FileNotFoundError, when it does not "
          "exist; FileError, an OSError, when it cannot be opened).")
      .def_static(
          "from_spec",
          [](const py::object& spec) { return model_from_spec_argument(spec, "spec"); },
          py::arg("spec"),
          "A model as the CLI's --model names it: 'paper', 'illustrative' or a model JSON path.")
      .def(
          "to_json", [](const Model& model) { return to_python(model.to_json()); },
          "The model JSON as a dict: {format, name, mass_kg, terms: [...]}.")
      .def(
          "save",
          [](const Model& model, const py::object& path) {
            analysis::save_model(model, path_string(path));
          },
          py::arg("path"), "Writes the model JSON file (as `oscilab-cli model ... --out`).")
      .def_property_readonly("name", &Model::name, "The model's name.")
      .def_property_readonly("mass_kg", &Model::mass_kg, "Mass m [kg].");
  bind_model_queries(cls);
}

}  // namespace oscilab::python
