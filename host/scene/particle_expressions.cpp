#include "host/scene/particle_expressions.hpp"

#include <map>

#include "host/expr/expression_error.hpp"
#include "host/scene/particle_generator.hpp"
#include "host/scene/scene_error.hpp"
#include "kernels/expr/particle_variables.hpp"

namespace mfsd {

const expr::VariableTable& particle_variable_table() {
  static const expr::VariableTable table{
      {"x0", "y0", "z0", "x", "y", "z", "ux", "uy", "uz", "vx", "vy", "vz", "t", "dt", "dx"}};
  static_assert(kParticleVariables == 15, "the table lists every ParticleVariable");
  return table;
}

expr::Program compile_particle_expression(const std::string& text, const Scene& scene, size_t body,
                                          const std::string& path) {
  std::map<std::string, double> constants;
  for (auto& kv : body_expression_constants(scene, body)) constants[kv.first] = kv.second;
  try {
    return expr::compile(text, particle_variable_table(), constants);
  } catch (const expr::ExpressionError& e) {
    throw SceneError(path + ": " + e.what());
  }
}

bool reads_only_reference_position(const expr::Program& program) {
  for (const expr::Instr& in : program.code())
    if (in.op == expr::Op::load_var && in.arg > var_z0) return false;
  return true;
}

}  // namespace mfsd
