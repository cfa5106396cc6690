// The distributed bookkeeping of ParticleSolver (docs/distributed.md): the
// ghost exchange's indices in the solver's order, the refresh of the
// ghosts' fields from their owners (the fields each stage refreshes are in
// the method's step recipe), migrations of particles between ranks and the
// membership that follows them, the step statistics over all ranks, and
// the test-only halo check. Included at the end of particle_solver.hpp.
#pragma once

namespace mfsd {

template <class B, int D, class Real>
void ParticleSolver<B, D, Real>::bind_ghosts() {
  if (!ghosts_) return;
  const std::vector<Index> where = locate();
  std::vector<Index> send, receive;
  for (long id : ghosts_->send_ids()) send.push_back(where[size_t(id)]);
  for (long id : ghosts_->receive_ids()) receive.push_back(where[size_t(id)]);
  from_host<B>(send, ghost_send_index_);
  from_host<B>(receive, ghost_receive_index_);
}

template <class B, int D, class Real>
void ParticleSolver<B, D, Real>::refresh_all_ghosts() {
  if (!ghosts_) return;
  std::vector<std::string> names;
  for (const std::string& name : particles_.field_names())
    if (name != field::id && name != field::ghost && name != field::reference_position_double) names.push_back(name);
  refresh_ghosts(names);
}

template <class B, int D, class Real>
void ParticleSolver<B, D, Real>::refresh_ghosts(const std::vector<std::string>& names) {
  if (!ghosts_) return;
  std::vector<std::string> fields;
  std::vector<std::vector<char>> packed;
  std::vector<size_t> size;  // bytes per element
  for (const std::string& name : names)
    if (particles_.has(name)) {
      fields.push_back(name);
      packed.push_back(particles_.pack(name, ghost_send_index_));
      size.push_back(particles_.element_bytes(name));
    }
  if (fields.empty()) return;
  size_t record = 0;
  for (size_t s : size) record += s;
  const std::vector<int>& sends = ghosts_->send_counts();
  const std::vector<int>& receives = ghosts_->receive_counts();
  std::vector<char> message;
  message.reserve(ghosts_->send_ids().size() * record);
  size_t first = 0;  // the rank's first element in send order
  for (int count : sends) {
    for (size_t f = 0; f < fields.size(); ++f) {
      const char* p = packed[f].data() + first * size[f];
      message.insert(message.end(), p, p + size_t(count) * size[f]);
    }
    first += size_t(count);
  }
  std::vector<char> received;
  ghosts_->exchange(message, record, received);
  std::vector<std::vector<char>> unpacked(fields.size());
  for (size_t f = 0; f < fields.size(); ++f) unpacked[f].reserve(ghosts_->receive_ids().size() * size[f]);
  const char* p = received.data();
  for (int count : receives)
    for (size_t f = 0; f < fields.size(); ++f) {
      unpacked[f].insert(unpacked[f].end(), p, p + size_t(count) * size[f]);
      p += size_t(count) * size[f];
    }
  for (size_t f = 0; f < fields.size(); ++f) particles_.unpack(fields[f], ghost_receive_index_, unpacked[f]);
}

template <class B, int D, class Real>
void ParticleSolver<B, D, Real>::migrate_particles(double radius) {
  const Index n = particles_.size();
  const auto ghost = to_host<B>(particles_.template buffer<unsigned char>(field::ghost));
  const auto ids = to_host<B>(particles_.template buffer<Index>(field::id));
  const auto X = to_host<B>(particles_.template buffer<Vec<D, Real>>(field::reference_position));
  const auto u = to_host<B>(particles_.template buffer<Vec<D, Real>>(field::displacement));
  std::vector<Index> owned_index;
  std::vector<long> owned;
  std::vector<std::array<double, 3>> position;
  for (Index i = 0; i < n; ++i)
    if (!ghost[size_t(i)]) {
      owned_index.push_back(i);
      owned.push_back(long(ids[size_t(i)]));
      std::array<double, 3> x{0, 0, 0};
      for (int a = 0; a < D; ++a) x[size_t(a)] = double(X[size_t(i)].v[a] + u[size_t(i)].v[a]);
      position.push_back(x);
    }
  // One record per owned particle: its fields one after the other (the
  // same names, in the same order, on every rank).
  std::vector<std::string> names;
  for (const std::string& name : particles_.field_names())
    if (name != field::id && name != field::ghost) names.push_back(name);
  std::vector<size_t> offset, size;
  size_t record = 0;
  for (const std::string& name : names) {
    offset.push_back(record);
    size.push_back(particles_.element_bytes(name));
    record += size.back();
  }
  DeviceVector<B, Index> pick;
  from_host<B>(owned_index, pick);
  std::vector<char> records(owned.size() * record);
  for (size_t f = 0; f < names.size(); ++f) {
    const std::vector<char> packed = particles_.pack(names[f], pick);
    for (size_t k = 0; k < owned.size(); ++k)
      std::memcpy(records.data() + k * record + offset[f], packed.data() + k * size[f], size[f]);
  }
  GhostExchange::Arrivals in = ghosts_->migrate(owned, position, records, record, radius);

  // The arrivals into the fields, then into the single-process order.
  const Index m = Index(in.global_id.size());
  particles_.resize(m);
  DeviceVector<B, Index> all;
  all.resize(size_t(m));
  sequence<B, Index>(all);
  for (size_t f = 0; f < names.size(); ++f) {
    std::vector<char> bytes(size_t(m) * size[f]);
    for (size_t k = 0; k < size_t(m); ++k)
      std::memcpy(bytes.data() + k * size[f], in.records.data() + k * record + offset[f], size[f]);
    particles_.unpack(names[f], all, bytes);
  }
  const auto body = to_host<B>(particles_.template buffer<int>(field::body));
  const auto key = to_host<B>(particles_.template buffer<std::int64_t>(field::order_key));
  std::vector<Index> order(static_cast<size_t>(m));
  std::iota(order.begin(), order.end(), Index(0));
  std::sort(order.begin(), order.end(), [&](Index a, Index b) {
    return std::make_tuple(body[size_t(a)], key[size_t(a)], in.global_id[size_t(a)]) <
           std::make_tuple(body[size_t(b)], key[size_t(b)], in.global_id[size_t(b)]);
  });
  DeviceVector<B, Index> perm;
  from_host<B>(order, perm);
  particles_.permute(perm);
  std::vector<long> global(static_cast<size_t>(m));
  for (size_t k = 0; k < size_t(m); ++k) global[k] = in.global_id[size_t(order[k])];
  ghosts_->adopt(global);

  follow_membership();
}

template <class B, int D, class Real>
void ParticleSolver<B, D, Real>::follow_membership() {
  sequence<B, Index>(particles_.template buffer<Index>(field::id));
  from_host<B>(ghosts_->ghost_mask(), particles_.template buffer<unsigned char>(field::ghost));
  const auto body = to_host<B>(particles_.template buffer<int>(field::body));
  for (size_t b = 0; b < ranges_.size(); ++b) {
    const auto lo = std::lower_bound(body.begin(), body.end(), int(b));
    const auto hi = std::upper_bound(body.begin(), body.end(), int(b));
    ranges_[b] = BodyRange{Index(lo - body.begin()), Index(hi - body.begin())};
  }
  const InitialParticles& lists = ghosts_->lists();
  init_.probe_particles = lists.probe_particles;
  init_.clamp_particles = lists.clamp_particles;
  init_.measure_particles = lists.measure_particles;
  init_.condition_particles = lists.condition_particles;
  bind_ghosts();
  const std::vector<Index> where = locate();
  conditions_.setup(init_, where, particles_.template get<Index>(field::id), ranges_);
  locate_probes(where);
  after_migration();
}

template <class B, int D, class Real>
void ParticleSolver<B, D, Real>::maxima_over_ranks(StepStatistics<Real>& s) {
  if (!ghosts_) return;
  std::vector<double> v{double(s.max_speed2), double(s.max_acceleration2), double(s.max_inverse_stretch),
                        double(s.max_stiffening)};
  ghosts_->max_over_ranks(v);
  s.max_speed2 = Real(v[0]), s.max_acceleration2 = Real(v[1]);
  s.max_inverse_stretch = Real(v[2]), s.max_stiffening = Real(v[3]);
}

template <class B, int D, class Real>
void ParticleSolver<B, D, Real>::verify_halo(const std::vector<Vec<D, Real>>& x, const std::vector<double>& support,
                                             bool across_bodies) {
  const auto ids = to_host<B>(particles_.template buffer<Index>(field::id));
  std::vector<long> global;
  std::vector<std::array<double, 3>> position;
  for (size_t i = 0; i < ids.size(); ++i) {
    global.push_back(ghosts_->global_id(long(ids[i])));
    std::array<double, 3> p{0, 0, 0};
    for (int a = 0; a < D; ++a) p[size_t(a)] = double(x[i].v[a]);
    position.push_back(p);
  }
  const std::string missing = distributed::missing_partner(
      *ghosts_, global, to_host<B>(particles_.template buffer<unsigned char>(field::ghost)),
      to_host<B>(particles_.template buffer<int>(field::body)), position, support, D, across_bodies);
  if (!missing.empty())
    throw std::logic_error(std::string("distributed ") + to_string(scene_.solver.method) + " halo incomplete at step " +
                           std::to_string(steps_) + ": " + missing);
}
}  // namespace mfsd
