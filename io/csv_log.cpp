#include "dnurbs/io/csv_log.h"

#include <cstdio>
#include <sstream>
#include <utility>

#include "dnurbs/core/error.h"
#include "dnurbs/io/atomic_write.h"

namespace dnurbs {

CsvLog::CsvLog(std::vector<std::string> columns) : columns_(std::move(columns)) {}

void CsvLog::add_row(int step, const std::vector<double>& values) {
  if (values.size() != columns_.size()) {
    throw make_error("CSV log row of ", values.size(), " values for ", columns_.size(), " columns");
  }
  std::string line = std::to_string(step);
  char buffer[32];
  for (double value : values) {
    std::snprintf(buffer, sizeof(buffer), ",%.17g", value);
    line += buffer;
  }
  line += '\n';
  rows_.emplace_back(step, std::move(line));
}

std::string CsvLog::header() const {
  std::string line = "step";
  for (const auto& column : columns_) {
    line += ',';
    line += column;
  }
  line += '\n';
  return line;
}

std::string CsvLog::to_string() const {
  std::string text = header();
  for (const auto& row : rows_) {
    text += row.second;
  }
  return text;
}

bool CsvLog::continue_from(const std::string& text, int last_step) {
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line) || line + "\n" != header()) {
    return false;
  }
  std::vector<std::pair<int, std::string>> rows;
  while (std::getline(in, line)) {
    if (line.empty()) {
      continue;
    }
    int step = 0;
    try {
      step = std::stoi(line.substr(0, line.find(',')));
    } catch (const std::exception&) {
      return false;
    }
    if (step <= last_step) {
      rows.emplace_back(step, line + "\n");
    }
  }
  rows_ = std::move(rows);
  return true;
}

void CsvLog::write(const std::filesystem::path& path) const {
  write_file_atomically(path, to_string());
}

}  // namespace dnurbs
