#include "host/driver/restart_hint.hpp"

#include <sstream>

namespace mfsd {

std::string shell_quote(const std::string& text) {
  if (!text.empty() && text.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789"
                                              "_-+=.,/:@%") == std::string::npos)
    return text;
  std::string q = "'";
  for (char c : text) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string restart_command(const SceneDocument& doc, const RunOptions& options, const std::string& dir) {
  std::ostringstream s;
  s << "mfsd run";
  if (doc.source_name.rfind('<', 0) != 0) s << ' ' << shell_quote(doc.source_name);  // not "<default scene>"
  for (const auto& o : doc.overrides) s << " --set " << shell_quote(o);
  const SolverOptions& so = options.solver;
  if (options.precision_given)
    s << " --precision " << (so.precision == Precision::single_precision ? "float" : "double");
  if (so.backend != "cpu") s << " --backend " << so.backend;
  if (so.threads > 0) s << " --threads " << so.threads;
  if (!so.packed_genog_record) s << " --genog-record scalar";
  if (so.pair_layout == SolverOptions::PairLayout::sliced)
    s << " --pair-layout sliced";
  else if (so.pair_loop != SolverOptions::PairLoop::automatic)
    s << " --pair-loop " << (so.pair_loop == SolverOptions::PairLoop::half ? "half" : "full");
  if (so.pair_precision == SolverOptions::PairPrecision::single) s << " --pair-precision float";
  if (options.checkpoint_every_minutes > 0) s << " --checkpoint-every " << options.checkpoint_every_minutes;
  if (options.quiet) s << " -q";
  s << " --restart " << shell_quote(dir);
  return s.str();
}

}  // namespace mfsd
