#include "host/output/pvd_index.hpp"

#include <iomanip>
#include <sstream>

#include "host/output/atomic_file.hpp"

namespace mfsd {

void PvdIndex::add(double time, const std::string& relative_file) {
  entries_.emplace_back(time, relative_file);
  write();
}

void PvdIndex::restore(std::vector<Entry> entries) {
  entries_ = std::move(entries);
  write();
}

void PvdIndex::write() const {
  std::ostringstream s;
  s << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
    << "  <Collection>\n";
  for (auto& e : entries_)
    s << "    <DataSet timestep=\"" << std::setprecision(12) << e.first << "\" part=\"0\" file=\"" << e.second
      << "\"/>\n";
  s << "  </Collection>\n</VTKFile>\n";
  write_file_atomically(path_, s.str());
}

}  // namespace mfsd
