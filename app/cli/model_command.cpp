// oscilab-cli model paper|illustrative|FILE [--out MODEL.json] [--summary S.json]
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>

#include "analysis/common/input_error.h"
#include "analysis/model/model_json.h"
#include "app/cli/commands.h"
#include "app/cli/output_files.h"

namespace oscilab::cli {
namespace {

struct ModelOptions {
  std::string spec;
  std::string out_path;
  std::string summary_path;
};

void run(const ModelOptions& options) {
  const analysis::Model model = analysis::model_from_spec(options.spec);
  const nlohmann::json summary = analysis::model_summary(model);
  std::printf("model %s: m = %g kg, %zu terms\n", model.name().c_str(), model.mass_kg(),
              model.terms().size());
  for (const auto& term : model.terms()) std::printf("  %s\n", term->to_json().dump().c_str());
  std::printf("equilibria (K(z*) = 0, eq. (2)):\n");
  for (const auto& e : summary["equilibria"]) {
    if (e["stable"].get<bool>()) {
      std::printf("  z* = %+.6f m  stable    f_lin = %.3f Hz (eq. (4))\n", e["z_m"].get<double>(),
                  e["linear_frequency_hz"].get<double>());
    } else {
      std::printf("  z* = %+.6f m  unstable\n", e["z_m"].get<double>());
    }
  }
  // Both files complete under temporary names before either takes its own.
  OutputFiles outputs;
  if (!options.out_path.empty()) {
    outputs.write(options.out_path,
                  [&](std::ostream& out) { out << model.to_json().dump(2) << '\n'; });
  }
  if (!options.summary_path.empty()) {
    outputs.write(options.summary_path, [&](std::ostream& out) { out << summary.dump(2) << '\n'; });
  }
  outputs.commit();
}

}  // namespace

void add_model_command(CLI::App& app) {
  auto options = std::make_shared<ModelOptions>();
  CLI::App* command = app.add_subcommand(
      "model",
      "Show a model (the paper's eq. (7) with Tables 1 and 3, the illustrative eq. (14) "
      "with Table 2, or a model JSON file), its equilibria and linear frequencies");
  command->add_option("model", options->spec, "paper | illustrative | MODEL.json")->required();
  command->add_option("--out", options->out_path, "write the model as JSON (oscilab-model/1)");
  command->add_option("--summary", options->summary_path,
                      "write {mass_kg, equilibria: [{z_m, stable, linear_frequency_hz}]} as JSON");
  command->callback([options] { run(*options); });
}

}  // namespace oscilab::cli
