// CSV time-history tables (energies, residuals, ...). The whole table is kept in memory and
// the file rewritten atomically on each append, so a plotting script reading it mid-run never
// sees a half-written last row. Tables are small (one row per step), so this costs little.
#include <cstdio>
#include <stdexcept>

#include "io_util.hpp"

namespace mlshell {
namespace {

// RFC 4180: a field containing a comma, quote or line break is enclosed in quotes, with
// embedded quotes doubled.
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
  return out;
}

}  // namespace

CsvTable::CsvTable(std::filesystem::path path, std::vector<std::string> columns)
    : path_(std::move(path)), columns_(std::move(columns)) {
  if (columns_.empty()) throw std::invalid_argument("CsvTable: no columns");
  for (std::size_t i = 0; i < columns_.size(); ++i) {
    if (i) text_ += ',';
    text_ += csv_field(columns_[i]);
  }
  text_ += '\n';
  // Written now so that a run that stops before its first row still leaves a valid table.
  write_file_atomic(path_, text_);
}

void CsvTable::append(const std::vector<std::variant<double, long long, std::string>>& row) {
  if (row.size() != columns_.size())
    throw std::invalid_argument("CsvTable '" + path_.string() + "': row has " +
                                std::to_string(row.size()) + " values but the table has " +
                                std::to_string(columns_.size()) + " columns");
  std::string line;
  for (std::size_t i = 0; i < row.size(); ++i) {
    if (i) line += ',';
    if (const auto* d = std::get_if<double>(&row[i]))
      line += io_detail::format_double(*d);
    else if (const auto* n = std::get_if<long long>(&row[i]))
      line += std::to_string(*n);
    else
      line += csv_field(std::get<std::string>(row[i]));
  }
  line += '\n';
  // Commit the row to memory only once it is on disk, so a failed append can be retried
  // without duplicating it.
  write_file_atomic(path_, text_ + line);
  text_ += line;
}

}  // namespace mlshell
