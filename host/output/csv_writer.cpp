#include "host/output/csv_writer.hpp"

#include <cstdio>
#include <stdexcept>

namespace mfsd {

CsvWriter::CsvWriter(const std::string& path, const std::vector<std::string>& columns)
    : out_(path, std::ios::trunc), path_(path), columns_(columns.size()) {
  if (!out_) throw std::runtime_error("cannot write '" + path + "'");
  for (size_t k = 0; k < columns.size(); ++k) out_ << (k ? "," : "") << columns[k];
  out_ << "\n";
  out_.flush();
}

void CsvWriter::row(const std::vector<double>& values) {
  if (values.size() != columns_) throw std::logic_error("CsvWriter: row width differs from header in " + path_);
  char buf[32];
  for (size_t k = 0; k < values.size(); ++k) {
    std::snprintf(buf, sizeof buf, "%.10g", values[k]);
    out_ << (k ? "," : "") << buf;
  }
  out_ << "\n";
  out_.flush();
}

}  // namespace mfsd
