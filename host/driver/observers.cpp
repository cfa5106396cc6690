#include "host/driver/observers.hpp"

#include <algorithm>
#include <cstring>
#include <map>

#include "host/scene/scene_error.hpp"

namespace mfsd {

namespace {

// A field's values on the host as doubles, `components` per particle.
std::vector<double> host_values(Solver& solver, const FieldMemory& m) {
  std::string copy;
  const char* p = static_cast<const char*>(m.data);
  if (m.on_device) {
    copy = solver.field_bytes(m.name);
    p = copy.data();
  }
  const size_t n = m.count * size_t(m.components);
  std::vector<double> v(n);
  for (size_t k = 0; k < n; ++k) {
    const char* e = p + k * size_t(m.scalar_bytes);
    if (m.kind == 'f' && m.scalar_bytes == 8) {
      double d;
      std::memcpy(&d, e, 8);
      v[k] = d;
    } else if (m.kind == 'f' && m.scalar_bytes == 4) {
      float f;
      std::memcpy(&f, e, 4);
      v[k] = double(f);
    } else if (m.scalar_bytes == 8) {
      long long i;
      std::memcpy(&i, e, 8);
      v[k] = double(i);
    } else if (m.scalar_bytes == 4) {
      int i;
      std::memcpy(&i, e, 4);
      v[k] = double(m.kind == 'u' ? double(unsigned(i)) : double(i));
    } else {
      v[k] = double(static_cast<unsigned char>(*e));
    }
  }
  return v;
}

struct FieldTable {
  std::map<std::string, FieldMemory> fields;
  const FieldMemory& at(const std::string& name) const { return fields.at(name); }
};

FieldTable fields_of(Solver& solver) {
  FieldTable s;
  for (const FieldMemory& m : solver.fields()) s.fields[m.name] = m;
  return s;
}

std::vector<std::vector<double>> points_of(const ObserverSpec& o, int dim) {
  std::vector<std::vector<double>> p;
  for (const Point3& x : o.points) p.emplace_back(x.begin(), x.begin() + dim);
  return p;
}

}  // namespace

Observers::Observers(const Scene& scene, Solver& solver) : dim_(scene.dimension) {
  const FieldTable s = fields_of(solver);
  if (s.fields.empty())
    throw SceneError("/observers", "a scene of several methods or a distributed run",
                     "a single-process run of one method (observers read its fields; not gathered over ranks or "
                     "methods yet)");
  for (const char* needed : {"reference_position", "displacement", "volume", "body"})
    if (!s.fields.count(needed)) throw std::logic_error(std::string("observers: the solver has no field ") + needed);
  const std::vector<double> X = host_values(solver, s.at("reference_position"));
  const std::vector<double> V = host_values(solver, s.at("volume"));
  const std::vector<double> body = host_values(solver, s.at("body"));
  for (size_t k = 0; k < scene.observers.size(); ++k) {
    Observed o;
    o.spec = scene.observers[k];
    const std::string path = "/observers/" + std::to_string(k);
    double support = 0;
    for (size_t b = 0; b < scene.bodies.size(); ++b) {
      const double h = scene.solver.h_over_dp * scene.bodies[b].spacing;
      if (scene.bodies[b].name == o.spec.body) o.body = int(b), support = 2.0 * h;
      if (o.spec.body.empty()) support = std::max(support, 2.0 * h);
    }
    o.radius = o.spec.radius > 0 ? o.spec.radius : support;
    for (size_t f = 0; f < o.spec.fields.size(); ++f) {
      const std::string& name = o.spec.fields[f];
      if (name == "position") {
        o.components.push_back(dim_);
        continue;
      }
      const auto it = s.fields.find(name);
      if (it == s.fields.end()) {
        std::string known = "\"position\"";
        for (const auto& kv : s.fields) known += ", \"" + kv.first + "\"";
        throw SceneError(path + "/fields/" + std::to_string(f), "\"" + name + "\"", "a field of this run: " + known);
      }
      o.components.push_back(it->second.components);
    }
    if (o.spec.freeze) {
      std::vector<unsigned char> use(V.size(), 1);
      if (o.body >= 0)
        for (size_t j = 0; j < use.size(); ++j) use[j] = int(body[j]) == o.body ? 1 : 0;
      o.frozen = observer_weights(points_of(o.spec, dim_), X, V, &use, dim_, o.radius,
                                  o.spec.interpolation == ObserverSpec::Interpolation::linear);
    }
    observed_.push_back(std::move(o));
  }
}

std::vector<std::string> Observers::columns() const {
  static const char* axis = "xyz";
  std::vector<std::string> c{"time"};
  for (const Observed& o : observed_)
    for (size_t p = 0; p < o.spec.points.size(); ++p) {
      const std::string point = o.spec.name + (o.spec.points.size() > 1 ? "." + std::to_string(p) : std::string());
      for (size_t f = 0; f < o.spec.fields.size(); ++f) {
        const std::string base = point + "." + o.spec.fields[f];
        const int n = o.components[f];
        if (n == 1) {
          c.push_back(base);
        } else if (n == dim_) {
          for (int a = 0; a < n; ++a) c.push_back(base + "." + axis[a]);
        } else {
          for (int a = 0; a < dim_; ++a)
            for (int b = 0; b < dim_; ++b) c.push_back(base + "." + axis[a] + axis[b]);
        }
      }
    }
  return c;
}

std::vector<double> Observers::row(Solver& solver, double time) const {
  const FieldTable s = fields_of(solver);
  const std::vector<double> X = host_values(solver, s.at("reference_position"));
  const std::vector<double> u = host_values(solver, s.at("displacement"));
  std::vector<double> x(X.size());
  for (size_t k = 0; k < x.size(); ++k) x[k] = X[k] + u[k];
  std::map<std::string, std::vector<double>> cache{{"position", x}};
  auto values = [&](const std::string& name) -> const std::vector<double>& {
    auto it = cache.find(name);
    if (it == cache.end()) it = cache.emplace(name, host_values(solver, s.at(name))).first;
    return it->second;
  };
  std::vector<double> r{time};
  for (const Observed& o : observed_) {
    std::vector<std::vector<ObserverWeight>> moving;
    if (!o.spec.freeze) {
      const std::vector<double>& V = values("volume");
      const std::vector<double>& body = values("body");
      std::vector<unsigned char> use(V.size(), 1);
      if (o.body >= 0)
        for (size_t j = 0; j < use.size(); ++j) use[j] = int(body[j]) == o.body ? 1 : 0;
      moving = observer_weights(points_of(o.spec, dim_), x, V, &use, dim_, o.radius,
                                o.spec.interpolation == ObserverSpec::Interpolation::linear);
    }
    const auto& weights = o.spec.freeze ? o.frozen : moving;
    for (size_t p = 0; p < o.spec.points.size(); ++p)
      for (size_t f = 0; f < o.spec.fields.size(); ++f) {
        const std::vector<double> v = observe(weights[p], values(o.spec.fields[f]), o.components[f]);
        r.insert(r.end(), v.begin(), v.end());
      }
  }
  return r;
}

}  // namespace mfsd
