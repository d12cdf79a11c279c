#pragma once
// The run's CSV outputs (trace.csv, metrics.csv, background.csv) read back: a header row
// naming the columns, then rows of cells. Readers check the columns they rely on, so a file
// of another shape is an error naming the file and line, never a crash later on.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace orch {

class CsvTable {
 public:
  // Reads `path`. Throws OrchError ("file:line: ...") when it cannot be read, when a column
  // of `required` is not in the header, or when a row has another number of cells than the
  // header. An empty cell is kept as "" (a value that does not exist).
  static CsvTable read(const std::filesystem::path& path, const std::vector<std::string>& required = {});
  static CsvTable parse(std::string_view text, const std::string& name_for_messages,
                        const std::vector<std::string>& required = {});

  [[nodiscard]] const std::vector<std::string>& columns() const { return columns_; }
  [[nodiscard]] std::size_t rows() const { return rows_; }
  [[nodiscard]] std::optional<std::size_t> column(std::string_view name) const;
  [[nodiscard]] const std::string& cell(std::size_t row, std::size_t column) const {
    return cells_[row * columns_.size() + column];
  }
  // The cell as a number; nullopt when it is empty. Throws OrchError (file, line, column)
  // when it is not a number.
  [[nodiscard]] std::optional<double> number(std::size_t row, std::size_t column) const;
  [[nodiscard]] const std::string& name() const { return name_; }

 private:
  std::string name_;
  std::vector<std::string> columns_;
  std::vector<std::string> cells_;  // row-major
  std::size_t rows_ = 0;
};

// Splits "a,b,,c" into its cells (no quoting: the run's CSV files never quote).
std::vector<std::string> split_csv_line(std::string_view line);
// A header joined by commas, as the writers define it, split into column names.
std::vector<std::string> csv_columns(std::string_view header);

}  // namespace orch
