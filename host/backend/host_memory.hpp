// The host memory this process may use: physical memory, or less under
// ulimit -v / -d. Scene checks compare their memory estimates with it.
#pragma once
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>

namespace mfsd {

inline double host_memory_limit_bytes() {
  double bytes = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
  for (int resource : {RLIMIT_AS, RLIMIT_DATA}) {
    rlimit r{};
    if (getrlimit(resource, &r) == 0 && r.rlim_cur != RLIM_INFINITY) bytes = std::min(bytes, double(r.rlim_cur));
  }
  return bytes;
}

}  // namespace mfsd
