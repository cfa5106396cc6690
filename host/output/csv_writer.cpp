#include "host/output/csv_writer.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace mfsd {

namespace {
std::string header(const std::vector<std::string>& columns) {
  std::string h;
  for (size_t k = 0; k < columns.size(); ++k) h += (k ? "," : "") + columns[k];
  return h + "\n";
}
}  // namespace

CsvWriter::CsvWriter(const std::string& path, const std::vector<std::string>& columns)
    : path_(path), columns_(columns.size()) {
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_APPEND, 0644);
  if (fd_ < 0) throw std::runtime_error("cannot write '" + path + "': " + std::strerror(errno));
  write(header(columns));
}

CsvWriter::CsvWriter(const std::string& path, const std::vector<std::string>& columns, std::uint64_t keep_bytes)
    : path_(path), columns_(columns.size()) {
  std::ifstream in(path, std::ios::binary);
  std::string first;
  if (!in || !std::getline(in, first))
    throw std::runtime_error("'" + path + "' is missing or empty; the run cannot be continued into it");
  if (first + "\n" != header(columns))
    throw std::runtime_error("'" + path + "' has other columns than this run writes");
  in.seekg(0, std::ios::end);
  if (std::uint64_t(in.tellg()) < keep_bytes)
    throw std::runtime_error("'" + path + "' is shorter than at the checkpoint (" + std::to_string(keep_bytes) +
                             " bytes)");
  in.close();
  fd_ = ::open(path.c_str(), O_WRONLY | O_APPEND);
  if (fd_ < 0 || ::ftruncate(fd_, off_t(keep_bytes)) != 0)
    throw std::runtime_error("cannot write '" + path + "': " + std::strerror(errno));
  bytes_ = keep_bytes;
}

CsvWriter::~CsvWriter() {
  if (fd_ >= 0) ::close(fd_);
}

void CsvWriter::row(const std::vector<double>& values) {
  if (values.size() != columns_) throw std::logic_error("CsvWriter: row width differs from header in " + path_);
  std::string line;
  char buf[32];
  for (size_t k = 0; k < values.size(); ++k) {
    std::snprintf(buf, sizeof buf, "%s%.10g", k ? "," : "", values[k]);
    line += buf;
  }
  write(line + "\n");
}

// One write call per row (retried only for what a signal cut short).
void CsvWriter::write(const std::string& text) {
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t w = ::write(fd_, text.data() + done, text.size() - done);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) throw std::runtime_error("cannot write '" + path_ + "': " + std::strerror(errno));
    done += size_t(w);
  }
  bytes_ += text.size();
}

}  // namespace mfsd
