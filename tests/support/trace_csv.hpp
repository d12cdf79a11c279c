#pragma once
// trace.csv (and the run's other CSV files) as rows of named columns, for assertions on what
// happened in a run; read by the core's reader (orchestrator/results/csv_table.hpp).
#include <filesystem>
#include <string>
#include <vector>

#include "results/csv_table.hpp"

namespace orch::test {

class Trace {
 public:
  struct Row {
    const Trace* trace;
    std::size_t index;
    [[nodiscard]] const std::string& str(const std::string& column) const {
      return trace->table_.cell(index, trace->index(column));
    }
    [[nodiscard]] double num(const std::string& column) const { return std::stod(str(column)); }
    [[nodiscard]] int integer(const std::string& column) const { return std::stoi(str(column)); }
  };

  explicit Trace(const std::filesystem::path& path) : table_(CsvTable::read(path)) {
    for (const auto& c : table_.columns()) header_ += (header_.empty() ? "" : ",") + c;
    for (std::size_t r = 0; r < table_.rows(); ++r) rows_.push_back(Row{this, r});
  }
  Trace(const Trace&) = delete;  // rows point back to their trace
  Trace& operator=(const Trace&) = delete;

  [[nodiscard]] const std::string& header() const { return header_; }
  [[nodiscard]] const std::vector<Row>& rows() const { return rows_; }
  // Rows point back to their trace: a temporary trace's rows would dangle in a range-for
  // (`for (auto& r : Trace(p).actor(0))`), so name the trace.
  std::vector<Row> actor(int id) const&& = delete;
  [[nodiscard]] std::vector<Row> actor(int id) const& {
    std::vector<Row> out;
    for (const auto& r : rows_)
      if (r.integer("actor_id") == id) out.push_back(r);
    return out;
  }
  [[nodiscard]] std::size_t index(const std::string& column) const {
    const auto c = table_.column(column);
    if (!c) throw std::out_of_range("no column " + column + " in " + table_.name());
    return *c;
  }

 private:
  CsvTable table_;
  std::string header_;
  std::vector<Row> rows_;
};

}  // namespace orch::test
