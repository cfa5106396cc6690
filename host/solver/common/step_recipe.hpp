// A method's step as data (design.md, "Inside host/"; docs/architecture.md,
// "Step recipes"): the stages in the order they run, each with the
// equations it implements and the fields whose ghost copies a distributed
// run refreshes from their owners before and after it. The stage runner
// (ParticleSolver::run) reads the table, so a method's step code names its
// stages and kernels and never the halo; the table is the one place that
// says which pass a ghost's cut row gets wrong and what its partners read.
// Each method's table is host/solver/<method>/<method>_recipe.cpp.
#pragma once
#include <string>
#include <utility>
#include <vector>

namespace mfsd {

struct StageRecipe {
  StageRecipe(std::string name_, std::string implements_, std::vector<std::string> before = {},
              std::vector<std::string> after = {}, bool present_ = true)
      : name(std::move(name_)),
        implements(std::move(implements_)),
        refresh_before(std::move(before)),
        refresh_after(std::move(after)),
        present(present_) {}

  std::string name;        // the stage's timer and device-error name
  std::string implements;  // its kernels and equations (formulations.md, seeds)
  // Distributed runs: the fields whose ghost copies are refreshed from the
  // owners before the stage (read of partners by its sums) and after it
  // (a ghost's own cut row got them wrong, and a later sum reads them).
  std::vector<std::string> refresh_before, refresh_after;
  bool present = true;  // false where this scene never runs the stage
};

class StepRecipe {
 public:
  StepRecipe() = default;
  explicit StepRecipe(std::vector<StageRecipe> stages) : stages_(std::move(stages)) {}

  const std::vector<StageRecipe>& stages() const { return stages_; }

  // The stage of this name, or null (the engine's own: halo, migrate).
  const StageRecipe* find(const char* name) const {
    for (const StageRecipe& s : stages_)
      if (s.name == name) return &s;
    return nullptr;
  }

  // The recipe as text, one stage per line with its equations and halo
  // refreshes (mfsd check --verbose, docs/architecture.md).
  std::string describe() const {
    std::string out;
    for (const StageRecipe& s : stages_) {
      if (!s.present) continue;
      out += "  " + s.name + std::string(s.name.size() < 17 ? 17 - s.name.size() : 1, ' ') + s.implements + "\n";
      auto list = [&](const char* when, const std::vector<std::string>& names) {
        if (names.empty()) return;
        out += std::string(19, ' ') + "halo " + when + ":";
        for (const std::string& n : names) out += " " + n;
        out += "\n";
      };
      list("before", s.refresh_before);
      list("after", s.refresh_after);
    }
    return out;
  }

 private:
  std::vector<StageRecipe> stages_;
};

}  // namespace mfsd
