// A scene as text: JSON parsed with line and column in its errors (and
// refused before parsing when nested or wide beyond reason), the --set
// overrides applied to it, the file read (refused when it cannot fit in
// memory), and the names that become file names checked.
#include <sys/resource.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "host/scene/nearest_name.hpp"
#include "host/scene/scene_error.hpp"
#include "host/scene/scene_reader.hpp"

namespace mfsd {

namespace {

void line_column(const std::string& text, size_t byte, size_t& line, size_t& column) {
  line = 1;
  column = 1;
  for (size_t k = 0; k < byte && k < text.size(); ++k) {
    if (text[k] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
}

// Arrays and objects nested deeper than this are refused before parsing: a
// parsed document is destroyed recursively, and a scene never needs it.
constexpr int kMaxJsonDepth = 256;
// Objects with more keys than this too: the parser's ordered objects insert
// a key in O(keys) (100,000 constants took minutes).
constexpr long kMaxObjectKeys = 10000;

// Throws a SceneError at the first bracket nested deeper than kMaxJsonDepth,
// or at the key beyond kMaxObjectKeys of an object (brackets and commas
// inside strings do not count).
// Scans JSON text one character at a time: inside() is true for the
// characters of a string literal, its quotes included.
struct JsonStrings {
  bool in_string = false, escaped = false;
  bool inside(char c) {
    if (in_string) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        in_string = false;
      return true;
    }
    if (c == '"') in_string = true;
    return in_string;
  }
};

void check_json_depth(const std::string& text, const std::string& source_name) {
  int depth = 0;
  JsonStrings strings;
  std::vector<long> keys;  // per open bracket: commas so far in an object, -1 in an array
  auto fail = [&](size_t k, const std::string& what) {
    size_t line, column;
    line_column(text, k, line, column);
    throw SceneError(source_name + ":" + std::to_string(line) + ":" + std::to_string(column) +
                     ": invalid scene: " + what);
  };
  for (size_t k = 0; k < text.size(); ++k) {
    const char c = text[k];
    if (strings.inside(c)) continue;
    if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth)
        fail(k, "arrays and objects nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
      keys.push_back(c == '{' ? 0 : -1);
    }
    if (c == ',' && !keys.empty() && keys.back() >= 0 && ++keys.back() >= kMaxObjectKeys)
      fail(k, "an object with more than " + std::to_string(kMaxObjectKeys) + " keys");
    if (c == ']' || c == '}') {
      --depth;
      if (!keys.empty()) keys.pop_back();
    }
  }
}

// The first occurrence of `token` outside JSON strings that is a whole token
// (not part of a longer number or name); npos when there is none.
size_t find_outside_strings(const std::string& text, const std::string& token) {
  if (token.empty()) return std::string::npos;
  auto part = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '+'; };
  JsonStrings strings;
  for (size_t k = 0; k < text.size(); ++k) {
    const char c = text[k];
    if (strings.inside(c)) continue;
    if (text.compare(k, token.size(), token) == 0 && (k == 0 || !part(text[k - 1])) &&
        (k + token.size() >= text.size() || !part(text[k + token.size()])))
      return k;
  }
  return std::string::npos;
}

}  // namespace

Json parse_scene_json(const std::string& text, const std::string& source_name) {
  check_json_depth(text, source_name);
  try {
    return Json::parse(text, nullptr, true, /*ignore_comments=*/true);
  } catch (const Json::out_of_range& e) {  // e.g. a number beyond the double range, -1e999
    std::string what = e.what();
    const auto p = what.find("] ");
    if (p != std::string::npos) what = what.substr(p + 2);
    // The exception has no position: the number it quotes is found in the text.
    std::string where;
    const auto q0 = what.find('\''), q1 = what.rfind('\'');
    if (q0 != std::string::npos && q1 > q0) {
      const size_t at = find_outside_strings(text, what.substr(q0 + 1, q1 - q0 - 1));
      if (at != std::string::npos) {
        size_t line, column;
        line_column(text, at, line, column);
        where = ":" + std::to_string(line) + ":" + std::to_string(column);
      }
    }
    throw SceneError(source_name + where + ": invalid JSON: " + what + " (numbers must be finite doubles)");
  } catch (const Json::parse_error& e) {
    size_t line, column;
    line_column(text, e.byte > 0 ? e.byte - 1 : 0, line, column);
    // nlohmann's text repeats the position: keep what follows "column N: ".
    std::string what = e.what();
    const auto p = what.find("column ");
    if (p != std::string::npos && what.find(": ", p) != std::string::npos) what = what.substr(what.find(": ", p) + 2);
    throw SceneError(source_name + ":" + std::to_string(line) + ":" + std::to_string(column) +
                     ": invalid JSON: " + what);
  }
}

void check_file_name(const std::string& path, const std::string& name, const std::string& used_in) {
  constexpr size_t kMaxLength = 200;
  bool ok = name.size() <= kMaxLength && name != "." && name != "..";
  for (char c : name) ok = ok && (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.');
  if (!ok)
    throw SceneError(path, json_text(Json(name)) + " (" + std::to_string(name.size()) + " characters)",
                     "a name of at most " + std::to_string(kMaxLength) +
                         " letters, digits, '_', '-' and '.', not \".\" or \"..\" (it names " + used_in + ")");
}

// The soft limit on this process's address space (ulimit -v), 0 when unlimited.
static unsigned long long address_space_limit() {
  rlimit r{};
  if (getrlimit(RLIMIT_AS, &r) != 0 || r.rlim_cur == RLIM_INFINITY) return 0;
  return static_cast<unsigned long long>(r.rlim_cur);
}

std::string path_of(const std::string& assignment) { return assignment.substr(0, assignment.find('=')); }

void apply_override(Json& doc, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw SceneError("--set " + assignment, "", "the form path=value, e.g. solver.hourglass=laplacian");
  const std::string path = assignment.substr(0, eq);
  const std::string text = assignment.substr(eq + 1);
  try {  // every string of a scene must be valid UTF-8 (run.json holds them)
    (void)Json(assignment).dump();
  } catch (const Json::type_error&) {
    throw SceneError("--set " + Json(path).dump(-1, ' ', true, Json::error_handler_t::replace),
                     "bytes that are not UTF-8", "UTF-8 text");
  }
  Json value;
  check_json_depth(text, "--set " + path_of(assignment));
  try {
    value = Json::parse(text);
  } catch (const Json::exception&) {
    value = text;  // a plain string such as laplacian (or a number beyond double range, refused where read)
  }
  std::vector<std::string> parts;
  std::stringstream ss(path);
  for (std::string p; std::getline(ss, p, '.');) {
    if (p.empty()) throw SceneError("--set " + path, "an empty path component", "names separated by '.'");
    parts.push_back(p);
  }
  Json* node = &doc;
  std::string walked;
  for (size_t k = 0; k < parts.size(); ++k) {
    const std::string& p = parts[k];
    const bool last = k + 1 == parts.size();
    walked += "/" + p;
    if (node->is_array()) {
      Json* next = nullptr;
      const bool numeric = p.find_first_not_of("0123456789") == std::string::npos;
      if (numeric && std::stoul(p) < node->size()) next = &(*node)[std::stoul(p)];
      for (auto& e : *node)
        if (!next && e.is_object() && e.contains("name") && e["name"] == p) next = &e;
      if (!next) {
        std::vector<std::string> names;
        for (auto& e : *node)
          if (e.is_object() && e.contains("name") && e["name"].is_string()) names.push_back(e["name"]);
        throw SceneError("--set " + path, "no element '" + p + "' at " + walked + did_you_mean(p, names),
                         "an index below " + std::to_string(node->size()) + " or the name of an element");
      }
      if (last) *next = value;
      node = next;
    } else if (node->is_object()) {
      // Constants are the one map of free names: a new one would be read,
      // used by nothing, and the study would change nothing (constants.dpp
      // for constants.dp). Every other key is checked by its reader.
      if (last && k == 1 && parts[0] == "constants" && !node->contains(p)) {
        std::vector<std::string> names;
        for (auto it = node->begin(); it != node->end(); ++it) names.push_back(it.key());
        std::string list;
        for (auto& n : names) list += (list.empty() ? "" : ", ") + n;
        throw SceneError("--set " + path, "no constant '" + p + "' in the scene" + did_you_mean(p, names),
                         names.empty() ? std::string("a scene with constants (this one has none)")
                                       : "one of its constants: " + list);
      }
      if (last) {
        if (value.is_null())
          node->erase(p);  // --set key=null removes the key: its default applies
        else
          (*node)[p] = value;
      } else {
        if (!node->contains(p)) (*node)[p] = Json::object();
        node = &(*node)[p];
      }
    } else {
      throw SceneError("--set " + path, json_type_name(*node) + " at " + walked,
                       "an object or an array to descend into");
    }
  }
}

SceneDocument load_scene_text(const std::string& text, const std::string& source_name,
                              const std::vector<std::string>& overrides, const std::string& base_dir) {
  SceneDocument d;
  d.source_name = source_name;
  d.overrides = overrides;
  d.source = parse_scene_json(text, source_name);
  if (!d.source.is_object()) throw SceneError(source_name, json_type_name(d.source), "a JSON object at the top level");
  for (auto& o : overrides) apply_override(d.source, o);
  d.scene = read_scene(d.source, d.resolved, base_dir);
  return d;
}

SceneDocument load_scene_file(const std::string& path, const std::vector<std::string>& overrides) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path, "", "a readable scene file (it cannot be opened)");
  // A file beyond the memory the process may use ended in "internal error:
  // std::bad_alloc" (a 7 GB scene under a 4 GB address-space limit): refuse
  // it with its size before reading, and name it if reading runs out anyway.
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  const auto too_big = [&](const std::string& why) {
    return SceneError(path, "a file of " + std::to_string(bytes) + " bytes",
                      "a scene file that fits in the memory this process may use (" + why + ")");
  };
  if (!ec) {
    const unsigned long long limit = address_space_limit();
    // The text, then the parsed document (several times the text) must fit.
    if (limit > 0 && bytes > limit / 4)
      throw too_big("its address space is limited to " + std::to_string(limit) +
                    " bytes; a scene needs about 4x its size");
  }
  std::string text;
  try {
    std::stringstream ss;
    ss << in.rdbuf();
    text = ss.str();
  } catch (const std::bad_alloc&) {
    throw too_big("reading it ran out of memory");
  }
  return load_scene_text(text, path, overrides, std::filesystem::path(path).parent_path().string());
}

}  // namespace mfsd
