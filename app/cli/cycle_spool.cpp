#include "app/cli/cycle_spool.h"

#include <cerrno>
#include <cstring>
#include <fstream>

#include "analysis/common/input_error.h"
#include "analysis/pipeline/cycle_table.h"

namespace oscilab::cli {
namespace {

using analysis::CycleTableRow;
using analysis::TableColumn;

// The cycle table's columns after the record's, which the spools hold.
const std::vector<TableColumn<CycleTableRow>>& spooled_columns() {
  static const std::vector<TableColumn<CycleTableRow>> columns = [] {
    const auto& all = analysis::cycle_table_columns();
    if (all.empty() || all.front().name != std::string("record")) {
      throw std::logic_error("the cycle table no longer starts with its record column");
    }
    return std::vector<TableColumn<CycleTableRow>>(all.begin() + 1, all.end());
  }();
  return columns;
}

}  // namespace

CycleSpool::CycleSpool(std::string target) : target_(std::move(target)) { spooled_columns(); }

CycleSpool::~CycleSpool() {
  for (auto& [record, spool] : spools_) {
    if (spool.stream) std::fclose(spool.stream);
  }
}

CycleSpool::Spool* CycleSpool::spool_of(std::size_t record) {
  const std::lock_guard lock(mutex_);
  if (!failure_.empty()) return nullptr;
  Spool& spool = spools_[record];
  if (!spool.file) {
    spool.file = std::make_unique<daq::TemporaryFile>(target_ + ".record" + std::to_string(record));
    spool.stream = std::fopen(spool.file->path().c_str(), "w");
    if (!spool.stream) {
      failure_ = target_ + ": cannot write: " + std::strerror(errno);
      return nullptr;
    }
  }
  return &spool;
}

void CycleSpool::add(std::size_t record, const analysis::CycleFit& cycle) noexcept {
  try {
    Spool* spool = spool_of(record);
    if (!spool) return;
    const std::string line = analysis::csv_line(spooled_columns(), CycleTableRow{nullptr, &cycle});
    if (std::fprintf(spool->stream, "%s\n", line.c_str()) < 0) {
      const std::lock_guard lock(mutex_);
      if (failure_.empty()) failure_ = target_ + ": write failed: " + std::strerror(errno);
    }
  } catch (const std::exception& error) {  // a string's allocation
    const std::lock_guard lock(mutex_);
    if (failure_.empty()) failure_ = target_ + ": write failed: " + error.what();
  }
}

void CycleSpool::write(const std::vector<std::string>& record_names,
                       const std::string& path) const {
  const std::lock_guard lock(mutex_);
  for (const auto& [record, spool] : spools_) {
    if (failure_.empty() && (std::fflush(spool.stream) != 0 || std::ferror(spool.stream))) {
      throw InputError(target_ + ": write failed: " + std::strerror(errno));
    }
  }
  if (!failure_.empty()) throw InputError(failure_);
  std::ofstream out(path, std::ios::binary);
  if (!out) throw InputError(target_ + ": cannot write: " + std::strerror(errno));
  out << analysis::csv_header(analysis::cycle_table_columns()) << '\n';
  const std::vector<TableColumn<CycleTableRow>> record_column(
      analysis::cycle_table_columns().begin(), analysis::cycle_table_columns().begin() + 1);
  std::string line;
  for (const auto& [record, spool] : spools_) {
    if (record >= record_names.size()) {
      throw std::logic_error("cycle spool: a record beyond the campaign's");
    }
    const std::string name =
        analysis::csv_line(record_column, CycleTableRow{&record_names[record], nullptr});
    std::ifstream in(spool.file->path(), std::ios::binary);
    if (!in) throw InputError(target_ + ": cannot read its spool: " + std::strerror(errno));
    while (std::getline(in, line)) out << name << ',' << line << '\n';
    if (in.bad()) throw InputError(target_ + ": cannot read its spool: " + std::strerror(errno));
  }
  out.close();
  if (!out) throw InputError(target_ + ": write failed: " + std::strerror(errno));
}

}  // namespace oscilab::cli
