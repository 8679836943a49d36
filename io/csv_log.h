#pragma once
// The CSV log of a scene run: one row per logged step (step number first, then doubles with 17
// significant digits), written whole and atomically, so a killed run leaves a complete file.

#include <filesystem>
#include <string>
#include <vector>

namespace dnurbs {

class CsvLog {
 public:
  /// `columns` are the names after the first column, "step".
  explicit CsvLog(std::vector<std::string> columns);
  const std::vector<std::string>& columns() const { return columns_; }
  /// Appends a row; throws Error if values.size() != columns().size().
  void add_row(int step, const std::vector<double>& values);
  int row_count() const { return static_cast<int>(rows_.size()); }
  /// The header line plus every row.
  std::string to_string() const;
  /// Takes the rows of an earlier log with the same header whose step is <= last_step (a
  /// resumed run continues its log). Returns false, keeping nothing, if the header differs.
  bool continue_from(const std::string& text, int last_step);
  /// Writes to_string() through a temporary file and a rename.
  void write(const std::filesystem::path& path) const;

 private:
  std::string header() const;
  std::vector<std::string> columns_;
  std::vector<std::pair<int, std::string>> rows_;  ///< step, formatted line (with newline)
};

}  // namespace dnurbs
