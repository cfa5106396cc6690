// Thrown when a run meets NaN/Inf or a particle leaves the scene's bounds.
// The CLI reports it and exits with code 3.
#pragma once
#include <stdexcept>
#include <string>

namespace mfsd {

class NumericalFailure : public std::runtime_error {
 public:
  NumericalFailure(long step, double time, long particle_id, const std::string& body, const std::string& field,
                   const std::string& detail)
      : std::runtime_error("step " + std::to_string(step) + " (t = " + std::to_string(time) + "): particle " +
                           std::to_string(particle_id) + " of body '" + body + "': " + field + " " + detail),
        step_(step),
        particle_id_(particle_id),
        time_(time),
        body_(body),
        field_(field),
        detail_(detail) {}
  long step() const { return step_; }
  long particle_id() const { return particle_id_; }
  double time() const { return time_; }
  const std::string& body() const { return body_; }
  const std::string& field() const { return field_; }
  const std::string& detail() const { return detail_; }
  // The same failure for the particle's id in another numbering (a part's
  // particle in the whole scene, host/solver/coupled/).
  NumericalFailure renumbered(long particle_id) const {
    return NumericalFailure(step_, time_, particle_id, body_, field_, detail_);
  }

 private:
  long step_;
  long particle_id_;
  double time_;
  std::string body_, field_, detail_;
};

}  // namespace mfsd
