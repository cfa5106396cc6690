// Hourglass-control variants of TLSPH (scene key solver.hourglass) as
// compile-time tags, so each force kernel holds only its own terms
// (style.md: model features as compile-time traits).
#pragma once
#include "kernels/core/config.hpp"

namespace mfsd {

struct HourglassNone {  // standard TLSPH (seed 000 eq. 20)
  static constexpr const char* name = "none";
};
struct HourglassLaplacian {  // hourglass-free Laplacian shear (seed 003 eq. 25-29)
  static constexpr const char* name = "laplacian";
};
struct HourglassGenog {  // generalized essentially non-hourglass (seed 000 eq. 25-34)
  static constexpr const char* name = "genog";
};

// GENOG correction weight phi_ij.
enum class GenogLimiter : int {
  paper = 0,   // phi = alpha d beta_ij gamma_ij, gamma = min(max(|e_hat|-0.05,0),1) (seed 000 eq. 32-33)
  capped = 1,  // phi = min(10 max(|e_hat| - 0.05, 0), 1) (the authors' later code)
};

// How the GENOG correction enters a pair's shear term.
enum class GenogForm : int {
  vector = 0,  // (S_i + S_j)(e0 + phi e_hat) dW V0 (seed 000 eq. 32)
  dyadic = 1,  // (S_i + S_j)(c (x) c) grad W V0, c = e0 + phi e_hat (the authors' later code)
};

}  // namespace mfsd
