#include "host/output/observer_weights.hpp"

#include <cmath>
#include <limits>
#include <unordered_map>

namespace mfsd {

namespace {

// Wendland C2 of support r (q = |d| / r in [0, 1]): (1 - q)^4 (1 + 4 q).
double wendland(double q) { return q >= 1.0 ? 0.0 : std::pow(1.0 - q, 4) * (1.0 + 4.0 * q); }

// Solves the (d + 1) x (d + 1) system M y = e_0 by Gaussian elimination with
// partial pivoting; false when M is singular to round-off.
bool solve_first_column(double M[4][4], int n, double y[4]) {
  double A[4][5];
  double scale = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) scale = std::max(scale, std::fabs(M[i][j]));
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) A[i][j] = M[i][j];
    A[i][n] = i == 0 ? 1.0 : 0.0;
  }
  for (int c = 0; c < n; ++c) {
    int p = c;
    for (int r = c + 1; r < n; ++r)
      if (std::fabs(A[r][c]) > std::fabs(A[p][c])) p = r;
    if (!(std::fabs(A[p][c]) > 1e-12 * scale)) return false;
    for (int j = 0; j <= n; ++j) std::swap(A[c][j], A[p][j]);
    for (int r = 0; r < n; ++r) {
      if (r == c) continue;
      const double f = A[r][c] / A[c][c];
      for (int j = c; j <= n; ++j) A[r][j] -= f * A[c][j];
    }
  }
  for (int i = 0; i < n; ++i) y[i] = A[i][n] / A[i][i];
  return true;
}

}  // namespace

std::vector<std::vector<ObserverWeight>> observer_weights(const std::vector<std::vector<double>>& points,
                                                          const std::vector<double>& x,
                                                          const std::vector<double>& volume,
                                                          const std::vector<unsigned char>* use, int dim, double radius,
                                                          bool linear) {
  const size_t n = volume.size();
  // Cells of the radius: each point looks at its 3^d neighbouring cells.
  auto cell_of = [&](const double* p) {
    long long key = 0;
    for (int a = 0; a < dim; ++a) key = key * 2097152LL + (long long)std::floor(p[a] / radius) + 1048576LL;
    return key;
  };
  std::unordered_map<long long, std::vector<size_t>> cells;
  for (size_t j = 0; j < n; ++j)
    if (!use || (*use)[j]) cells[cell_of(&x[size_t(dim) * j])].push_back(j);

  std::vector<std::vector<ObserverWeight>> out(points.size());
  for (size_t p = 0; p < points.size(); ++p) {
    const double* xp = points[p].data();
    std::vector<ObserverWeight>& w = out[p];
    long long base[3] = {0, 0, 0};
    for (int a = 0; a < dim; ++a) base[a] = (long long)std::floor(xp[a] / radius);
    const int span = dim == 3 ? 27 : 9;
    for (int c = 0; c < span; ++c) {
      long long key = 0;
      int rest = c;
      for (int a = 0; a < dim; ++a) {
        key = key * 2097152LL + base[a] + (rest % 3 - 1) + 1048576LL;
        rest /= 3;
      }
      const auto it = cells.find(key);
      if (it == cells.end()) continue;
      for (size_t j : it->second) {
        double r2 = 0;
        for (int a = 0; a < dim; ++a)
          r2 += (x[size_t(dim) * j + size_t(a)] - xp[a]) * (x[size_t(dim) * j + size_t(a)] - xp[a]);
        const double W = wendland(std::sqrt(r2) / radius);
        if (W > 0) w.push_back({j, W * volume[j]});
      }
    }
    double sum = 0;
    for (const auto& e : w) sum += e.weight;
    if (!(sum > 0)) {
      w.clear();
      continue;
    }
    bool corrected = false;
    if (linear) {
      // M = sum W V [1, d/r][1, d/r]^T (d scaled by r: a well-conditioned matrix)
      double M[4][4] = {};
      for (const auto& e : w) {
        double h[4] = {1, 0, 0, 0};
        for (int a = 0; a < dim; ++a) h[a + 1] = (x[size_t(dim) * e.particle + size_t(a)] - xp[a]) / radius;
        for (int i = 0; i <= dim; ++i)
          for (int k = 0; k <= dim; ++k) M[i][k] += e.weight * h[i] * h[k];
      }
      double y[4];
      if (solve_first_column(M, dim + 1, y)) {
        for (auto& e : w) {
          double c = y[0];
          for (int a = 0; a < dim; ++a) c += y[a + 1] * (x[size_t(dim) * e.particle + size_t(a)] - xp[a]) / radius;
          e.weight *= c;
        }
        corrected = true;
      }
    }
    if (!corrected)
      for (auto& e : w) e.weight /= sum;
  }
  return out;
}

std::vector<double> observe(const std::vector<ObserverWeight>& weights, const std::vector<double>& field,
                            int components) {
  std::vector<double> v(size_t(components), weights.empty() ? std::numeric_limits<double>::quiet_NaN() : 0.0);
  for (const auto& e : weights)
    for (int c = 0; c < components; ++c) v[size_t(c)] += e.weight * field[e.particle * size_t(components) + size_t(c)];
  return v;
}

}  // namespace mfsd
