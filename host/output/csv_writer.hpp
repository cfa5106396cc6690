// A CSV file with a header row. Each row goes to the file in one write and is
// flushed, so that a running simulation can be plotted, a failed one keeps its
// history, and a killed one leaves whole rows.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace mfsd {

class CsvWriter {
 public:
  // A new file with the header.
  CsvWriter(const std::string& path, const std::vector<std::string>& columns);
  // A continued run: the file as it was `keep_bytes` long (the header and the
  // rows up to a checkpoint), then appended to. Throws std::runtime_error when
  // the file is missing, shorter, or its header names other columns.
  CsvWriter(const std::string& path, const std::vector<std::string>& columns, std::uint64_t keep_bytes);
  ~CsvWriter();
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;

  void row(const std::vector<double>& values);
  size_t columns() const { return columns_; }
  std::uint64_t bytes() const { return bytes_; }  // the file's length

 private:
  void write(const std::string& text);
  int fd_ = -1;
  std::string path_;
  size_t columns_;
  std::uint64_t bytes_ = 0;
};

}  // namespace mfsd
