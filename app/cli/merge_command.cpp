// oscilab-cli merge FIT.json... --out TABLE.csv: many independent fits (a campaign run
// by Slurm or GNU parallel, scripts/) joined into one table, one row per fit.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>

#include "analysis/common/input_error.h"
#include "analysis/common/json_limits.h"
#include "analysis/identification/fit_report.h"
#include "analysis/identification/fit_table.h"
#include "app/cli/commands.h"
#include "app/cli/output_files.h"
#include "daq/recording/json_file.h"

namespace oscilab::cli {
namespace {

struct MergeOptions {
  std::vector<std::string> fits;
  std::string out_path;
};

void run(const MergeOptions& o) {
  refuse_output_over_inputs(o.out_path, "--out", o.fits);
  std::vector<analysis::FitSummary> rows;
  for (const auto& path : o.fits) {
    const nlohmann::json json = daq::read_json_file(path, kMaxJsonTextBytes);
    rows.push_back(analysis::read_fit_summary(json, path));
  }
  const analysis::FitTable table = analysis::fit_table(std::move(rows));
  // The table is complete before it is in place: a failed write leaves no file.
  OutputFiles outputs;
  std::ofstream out(outputs.add(o.out_path));
  if (!out) throw InputError(o.out_path + ": cannot write: " + std::strerror(errno));
  analysis::write_fit_table_csv(out, table);
  out.close();
  if (!out) throw InputError(o.out_path + ": write failed: " + std::strerror(errno));
  outputs.commit();
  std::printf("merged %zu fits into %s\n", table.rows.size(), o.out_path.c_str());
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
