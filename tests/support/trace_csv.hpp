#pragma once
// trace.csv as rows of named columns, for assertions on what happened in a run.
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace orch::test {

class Trace {
 public:
  struct Row {
    const Trace* trace;
    std::vector<std::string> cells;
    [[nodiscard]] const std::string& str(const std::string& column) const { return cells.at(trace->index(column)); }
    [[nodiscard]] double num(const std::string& column) const { return std::stod(str(column)); }
    [[nodiscard]] int integer(const std::string& column) const { return std::stoi(str(column)); }
  };

  explicit Trace(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error("no trace at " + path.string());
    std::getline(in, header_);
    columns_ = split(header_);
    for (std::size_t i = 0; i < columns_.size(); ++i) index_[columns_[i]] = i;
    std::string line;
    while (std::getline(in, line)) rows_.push_back(Row{this, split(line)});
  }

  [[nodiscard]] const std::string& header() const { return header_; }
  [[nodiscard]] const std::vector<Row>& rows() const { return rows_; }
  [[nodiscard]] std::vector<Row> actor(int id) const {
    std::vector<Row> out;
    for (const auto& r : rows_)
      if (r.integer("actor_id") == id) out.push_back(r);
    return out;
  }
  [[nodiscard]] std::size_t index(const std::string& column) const { return index_.at(column); }

 private:
  static std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> out;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) out.push_back(cell);
    if (!line.empty() && line.back() == ',') out.emplace_back();
    return out;
  }
  std::string header_;
  std::vector<std::string> columns_;
  std::map<std::string, std::size_t> index_;
  std::vector<Row> rows_;
};

}  // namespace orch::test
