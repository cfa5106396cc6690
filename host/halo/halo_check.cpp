#include "host/halo/halo_check.hpp"

#include <cmath>
#include <cstdlib>
#include <map>
#include <unordered_set>

namespace mfsd::distributed {

std::string missing_partner(GhostExchange& exchange, const std::vector<long>& global,
                            const std::vector<unsigned char>& ghost, const std::vector<int>& body,
                            const std::vector<std::array<double, 3>>& x, const std::vector<double>& support, int dim,
                            bool across_bodies) {
  std::vector<double> mine;
  for (size_t i = 0; i < global.size(); ++i)
    if (!ghost[i]) mine.insert(mine.end(), {double(global[i]), double(body[i]), x[i][0], x[i][1], x[i][2]});
  const std::vector<std::vector<double>> all = exchange.gather_all(mine);
  // Every owned particle of the scene in cells of the largest support.
  double cell = 0;
  for (double s : support) cell = std::max(cell, s);
  using Key = std::array<long, 3>;
  auto key = [&](const double* p) {
    Key k{0, 0, 0};
    for (int a = 0; a < dim; ++a) k[size_t(a)] = long(std::floor(p[a] / cell));
    return k;
  };
  std::vector<const double*> point;  // g, body, x, y, z
  for (const auto& r : all)
    for (size_t k = 0; k + 4 < r.size(); k += 5) point.push_back(r.data() + k);
  std::map<Key, std::vector<size_t>> cells;
  for (size_t p = 0; p < point.size(); ++p) cells[key(point[p] + 2)].push_back(p);
  const std::unordered_set<long> held(global.begin(), global.end());
  for (size_t i = 0; i < global.size(); ++i) {
    if (ghost[i]) continue;
    const double s = support[size_t(body[i])];
    const Key c = key(x[i].data());
    const int reach_z = dim == 3 ? 1 : 0, reach_y = dim >= 2 ? 1 : 0;
    for (long dx = -1; dx <= 1; ++dx)
      for (long dy = -reach_y; dy <= reach_y; ++dy)
        for (long dz = -reach_z; dz <= reach_z; ++dz) {
          const auto it = cells.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == cells.end()) continue;
          for (size_t p : it->second) {
            const double* q = point[p];
            if (!across_bodies && int(q[1]) != body[i]) continue;
            double d2 = 0;
            for (int a = 0; a < dim; ++a) d2 += (q[2 + a] - x[i][size_t(a)]) * (q[2 + a] - x[i][size_t(a)]);
            if (d2 < s * s && !held.count(long(q[0])))
              return "particle " + std::to_string(global[i]) + " misses partner " + std::to_string(long(q[0])) +
                     " at distance " + std::to_string(std::sqrt(d2)) + " (support " + std::to_string(s) + ")";
          }
        }
  }
  return {};
}

bool halo_check_requested() {
  const char* v = std::getenv("MFSD_VERIFY_HALO");
  return v && std::string(v) == "1";
}

}  // namespace mfsd::distributed

namespace mfsd::distributed {

bool migration_switched_off() {
  const char* v = std::getenv("MFSD_MIGRATE");
  return v && std::string(v) == "0";
}

}  // namespace mfsd::distributed
