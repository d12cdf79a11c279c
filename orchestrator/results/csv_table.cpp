#include "results/csv_table.hpp"

#include <fmt/format.h>

#include <charconv>

#include "core/errors.hpp"
#include "core/files.hpp"

namespace orch {

std::vector<std::string> split_csv_line(std::string_view line) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    out.emplace_back(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return out;
}

std::vector<std::string> csv_columns(std::string_view header) { return split_csv_line(header); }

CsvTable CsvTable::read(const std::filesystem::path& path, const std::vector<std::string>& required) {
  return parse(read_file(path), path.string(), required);
}

CsvTable CsvTable::parse(std::string_view text, const std::string& name, const std::vector<std::string>& required) {
  CsvTable t;
  t.name_ = name;
  std::size_t line_no = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line_no == 1) {
      t.columns_ = split_csv_line(line);
      continue;
    }
    if (line.empty()) continue;  // a trailing newline; a run cut short may end in one
    auto cells = split_csv_line(line);
    if (cells.size() != t.columns_.size())
      throw OrchError(fmt::format("{}:{}: {} cells, the header has {} columns", name, line_no, cells.size(),
                                  t.columns_.size()));
    for (auto& c : cells) t.cells_.push_back(std::move(c));
    ++t.rows_;
  }
  if (line_no == 0) throw OrchError(fmt::format("{}:1: empty file, expected a header row", name));
  for (const auto& r : required)
    if (!t.column(r))
      throw OrchError(fmt::format("{}:1: no column \"{}\" in the header (expected {})", name, r, fmt::join(required, ",")));
  return t;
}

std::optional<std::size_t> CsvTable::column(std::string_view name) const {
  for (std::size_t i = 0; i < columns_.size(); ++i)
    if (columns_[i] == name) return i;
  return std::nullopt;
}

std::optional<double> CsvTable::number(std::size_t row, std::size_t col) const {
  const std::string& s = cell(row, col);
  if (s.empty()) return std::nullopt;
  double v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size())
    throw OrchError(fmt::format("{}:{}: column {}: \"{}\" is not a number", name_, row + 2, columns_[col], s));
  return v;
}

}  // namespace orch
