#include "daq/recording/fit_json.h"

#include <fstream>

#include "analysis/common/input_error.h"
#include "analysis/identification/fit_report.h"
#include "daq/recording/temporary_file.h"

namespace oscilab::daq {

nlohmann::json fit_json(const analysis::FitResult& fit, const analysis::EdcObjective& objective,
                        const std::vector<std::string>& records,
                        const std::vector<std::string>& notes) {
  nlohmann::json report = analysis::fit_report_json(fit, objective, records);
  report["notes"] = notes;
  return report;
}

void write_fit_json(const std::string& path, const analysis::FitResult& fit,
                    const analysis::EdcObjective& objective,
                    const std::vector<std::string>& records,
                    const std::vector<std::string>& notes) {
  daq::TemporaryFile file(path);
  {
    std::ofstream out(file.path());
    out << fit_json(fit, objective, records, notes).dump(2) << '\n';
    out.close();
    if (!out) throw InputError(path + ": write failed");
  }
  file.commit();
}

}  // namespace oscilab::daq
