#include <omp.h>

#include "host/scene/scene_error.hpp"
#include "host/solver/solver.hpp"

namespace mfsd {

#define MFSD_DECLARE(backend, dim, real)                                                                  \
  std::unique_ptr<Solver> make_tlsph_##backend##_##dim##d_##real(const Scene&, const InitialParticles&,   \
                                                                 const SolverOptions&);                   \
  std::unique_ptr<Solver> make_ulsph_##backend##_##dim##d_##real(const Scene&, const InitialParticles&,   \
                                                                 const SolverOptions&);                   \
  std::unique_ptr<Solver> make_rkpm_##backend##_##dim##d_##real(const Scene&, const InitialParticles&,    \
                                                                const SolverOptions&);                    \
  std::unique_ptr<Solver> make_coupled_##backend##_##dim##d_##real(const Scene&, const InitialParticles&, \
                                                                   const SolverOptions&);
MFSD_DECLARE(cpu, 2, float)
MFSD_DECLARE(cpu, 2, double)
MFSD_DECLARE(cpu, 3, float)
MFSD_DECLARE(cpu, 3, double)
#if defined(MFSD_WITH_CUDA)
MFSD_DECLARE(cuda, 2, float)
MFSD_DECLARE(cuda, 2, double)
MFSD_DECLARE(cuda, 3, float)
MFSD_DECLARE(cuda, 3, double)
#endif
#undef MFSD_DECLARE

std::unique_ptr<Solver> make_solver(const Scene& given, const InitialParticles& p, const SolverOptions& o) {
  // Bodies all of the other method than solver.method: that method's settings (solver_for).
  Scene scene = given;
  if (!mixed_methods(given) && scene_method(given) != given.solver.method) {
    scene.solver = solver_for(given.solver, scene_method(given));
    if (!scene.solver.deformed_time_step_given) scene.solver.deformed_time_step = has_plastic_body(scene);
  }
  const bool single = o.precision == Precision::single_precision;
  const int d = scene.dimension;
  if (o.backend == "cpu") {
    if (o.threads > 0) omp_set_num_threads(o.threads);
    if (mixed_methods(scene)) {
      if (d == 2) return single ? make_coupled_cpu_2d_float(scene, p, o) : make_coupled_cpu_2d_double(scene, p, o);
      return single ? make_coupled_cpu_3d_float(scene, p, o) : make_coupled_cpu_3d_double(scene, p, o);
    }
    if (scene.solver.method == Method::rkpm) {
      if (d == 2) return single ? make_rkpm_cpu_2d_float(scene, p, o) : make_rkpm_cpu_2d_double(scene, p, o);
      return single ? make_rkpm_cpu_3d_float(scene, p, o) : make_rkpm_cpu_3d_double(scene, p, o);
    }
    if (scene.solver.method == Method::ulsph) {
      if (d == 2) return single ? make_ulsph_cpu_2d_float(scene, p, o) : make_ulsph_cpu_2d_double(scene, p, o);
      return single ? make_ulsph_cpu_3d_float(scene, p, o) : make_ulsph_cpu_3d_double(scene, p, o);
    }
    if (d == 2) return single ? make_tlsph_cpu_2d_float(scene, p, o) : make_tlsph_cpu_2d_double(scene, p, o);
    return single ? make_tlsph_cpu_3d_float(scene, p, o) : make_tlsph_cpu_3d_double(scene, p, o);
  }
  if (o.backend == "cuda") {
#if defined(MFSD_WITH_CUDA)
    if (cuda_device_count() <= 0)
      throw UsageError("--backend cuda: this machine has no usable CUDA device (" + cuda_device_name() +
                       "); use --backend cpu");
    if (mixed_methods(scene)) {
      if (d == 2) return single ? make_coupled_cuda_2d_float(scene, p, o) : make_coupled_cuda_2d_double(scene, p, o);
      return single ? make_coupled_cuda_3d_float(scene, p, o) : make_coupled_cuda_3d_double(scene, p, o);
    }
    if (scene.solver.method == Method::rkpm) {
      if (d == 2) return single ? make_rkpm_cuda_2d_float(scene, p, o) : make_rkpm_cuda_2d_double(scene, p, o);
      return single ? make_rkpm_cuda_3d_float(scene, p, o) : make_rkpm_cuda_3d_double(scene, p, o);
    }
    if (scene.solver.method == Method::ulsph) {
      if (d == 2) return single ? make_ulsph_cuda_2d_float(scene, p, o) : make_ulsph_cuda_2d_double(scene, p, o);
      return single ? make_ulsph_cuda_3d_float(scene, p, o) : make_ulsph_cuda_3d_double(scene, p, o);
    }
    if (d == 2) return single ? make_tlsph_cuda_2d_float(scene, p, o) : make_tlsph_cuda_2d_double(scene, p, o);
    return single ? make_tlsph_cuda_3d_float(scene, p, o) : make_tlsph_cuda_3d_double(scene, p, o);
#else
    throw UsageError(
        "--backend cuda: this mfsd binary was built without CUDA (no nvcc at build time); "
        "use --backend cpu or rebuild on a machine with the CUDA toolkit");
#endif
  }
  throw UsageError("--backend " + o.backend + ": expected cpu or cuda");
}

}  // namespace mfsd
