// oscilab-cli merge FIT.json... --out TABLE.csv: many independent fits (a campaign run
// by Slurm or GNU parallel, scripts/) joined into one table, one row per fit.
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <set>

#include "analysis/common/input_error.h"
#include "analysis/common/json_limits.h"
#include "analysis/identification/fit_report.h"
#include "app/cli/commands.h"
#include "app/cli/output_files.h"
#include "daq/recording/json_file.h"

namespace oscilab::cli {
namespace {

struct MergeOptions {
  std::vector<std::string> fits;
  std::string out_path;
};

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string value_or_empty(double value) {
  if (!std::isfinite(value)) return "";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", value);
  return buffer;
}

void run(const MergeOptions& o) {
  refuse_output_over_inputs(o.out_path, "--out", o.fits);
  std::vector<analysis::FitSummary> rows;
  std::vector<std::string> parameters;  // union, in first-seen order
  std::set<std::string> seen;
  for (const auto& path : o.fits) {
    const nlohmann::json json = daq::read_json_file(path, kMaxJsonTextBytes);
    rows.push_back(analysis::read_fit_summary(json, path));
    for (const auto& [name, value] : rows.back().parameters) {
      if (seen.insert(name).second) parameters.push_back(name);
    }
  }
  // The table is complete before it is in place: a failed write leaves no file.
  OutputFiles outputs;
  std::ofstream out(outputs.add(o.out_path));
  if (!out) throw InputError(o.out_path + ": cannot write: " + std::strerror(errno));
  out << "fit,records,method,cost_j,mean_deviation_pct_positive,mean_deviation_pct_negative,"
         "evaluations,seconds";
  for (const auto& p : parameters) out << ',' << p << ',' << p << "_std";
  out << '\n';
  for (const auto& r : rows) {
    out << csv_field(r.source) << ',' << csv_field(r.records) << ',' << csv_field(r.method) << ','
        << value_or_empty(r.cost_j) << ',' << value_or_empty(r.mean_deviation_pct_positive) << ','
        << value_or_empty(r.mean_deviation_pct_negative) << ',' << r.evaluations << ','
        << value_or_empty(r.seconds);
    for (const auto& p : parameters) {
      double value = std::nan(""), error = std::nan("");
      for (const auto& [name, v] : r.parameters) {
        if (name == p) value = v;
      }
      for (const auto& [name, e] : r.standard_errors) {
        if (name == p) error = e;
      }
      out << ',' << value_or_empty(value) << ',' << value_or_empty(error);
    }
    out << '\n';
  }
  out.close();
  if (!out) throw InputError(o.out_path + ": write failed: " + std::strerror(errno));
  outputs.commit();
  std::printf("merged %zu fits into %s\n", rows.size(), o.out_path.c_str());
}

}  // namespace

void add_merge_command(CLI::App& app) {
  auto o = std::make_shared<MergeOptions>();
  CLI::App* command = app.add_subcommand(
      "merge", "Join FIT JSONs of many fits (a campaign) into one CSV table, one row per fit");
  command->add_option("fits", o->fits, "FIT.json files written by oscilab-cli fit")->required();
  command->add_option("--out", o->out_path, "the table (CSV)")->required();
  command->callback([o] { run(*o); });
}

}  // namespace oscilab::cli
