#include "host/scene/json_node.hpp"

#include <cmath>
#include <sstream>

#include "host/scene/nearest_name.hpp"
#include "host/scene/scene_error.hpp"

namespace mfsd {

std::string json_text(const Json& v) {
  std::string s = v.dump(-1, ' ', false, Json::error_handler_t::replace);
  if (s.size() > 60) s = s.substr(0, 57) + "...";
  return s;
}

std::string json_type_name(const Json& v) {
  if (v.is_null()) return "null";
  if (v.is_boolean()) return "a boolean";
  if (v.is_number()) return "a number";
  if (v.is_string()) return "a string";
  if (v.is_array()) return "an array";
  return "an object";
}

JsonNode::JsonNode(const Json& value, std::string path, Json& resolved, ConstantEvaluator eval)
    : value_(&value), path_(std::move(path)), resolved_(&resolved), eval_(std::move(eval)) {
  if (!value.is_object()) throw SceneError(path_, json_type_name(value) + " " + json_text(value), "an object");
  if (!resolved_->is_object()) *resolved_ = Json::object();
}

bool JsonNode::has(const std::string& key) const { return value_->contains(key); }

const Json& JsonNode::required(const std::string& key) const {
  if (!value_->contains(key)) {
    std::vector<std::string> present;  // a misspelling of the key, e.g. poison_ratio for poisson_ratio
    for (auto it = value_->begin(); it != value_->end(); ++it)
      if (!known_.count(it.key())) present.push_back(it.key());
    const std::string hint = nearest_name(key, present);
    throw SceneError(key_path(key), hint.empty() ? "nothing" : "nothing, but '" + hint + "', an unknown key",
                     "this key (it is required)" + std::string(hint.empty() ? "" : "; did you mean '" + key + "'?"));
  }
  return (*value_)[key];
}

double JsonNode::to_number(const Json& v, const std::string& path) const {
  if (v.is_number()) return v.get<double>();
  if (v.is_string() && eval_) return eval_(v.get<std::string>(), path);
  throw SceneError(path, json_type_name(v) + " " + json_text(v),
                   eval_ ? "a number or an expression of the constants (string)" : "a number");
}

static void check_range(double x, const Range& r, const std::string& path, const Json& v) {
  if (!std::isfinite(x) || !r.contains(x)) {
    std::ostringstream s;
    s << json_text(v);
    if (!v.is_number()) s << " = " << x;
    throw SceneError(path, s.str(), r.text);
  }
}

double JsonNode::number(const std::string& key, const Range& range) {
  known_.insert(key);
  const Json& v = required(key);
  const double x = to_number(v, key_path(key));
  check_range(x, range, key_path(key), v);
  (*resolved_)[key] = x;
  return x;
}

double JsonNode::number(const std::string& key, double fallback, const Range& range) {
  if (!has(key)) {
    known_.insert(key);
    (*resolved_)[key] = fallback;
    return fallback;
  }
  return number(key, range);
}

long JsonNode::integer(const std::string& key, long fallback, long lo, long hi) {
  known_.insert(key);
  long x = fallback;
  if (has(key)) {
    const Json& v = (*value_)[key];
    if (!v.is_number_integer()) throw SceneError(key_path(key), json_type_name(v) + " " + json_text(v), "an integer");
    x = v.get<long>();
    if (x < lo || x > hi)
      throw SceneError(key_path(key), json_text(v),
                       "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  (*resolved_)[key] = x;
  return x;
}

bool JsonNode::boolean(const std::string& key, bool fallback) {
  known_.insert(key);
  bool x = fallback;
  if (has(key)) {
    const Json& v = (*value_)[key];
    if (!v.is_boolean()) throw SceneError(key_path(key), json_type_name(v) + " " + json_text(v), "true or false");
    x = v.get<bool>();
  }
  (*resolved_)[key] = x;
  return x;
}

std::string JsonNode::string(const std::string& key) {
  known_.insert(key);
  const Json& v = required(key);
  if (!v.is_string() || v.get<std::string>().empty())
    throw SceneError(key_path(key), json_type_name(v) + " " + json_text(v), "a non-empty string");
  (*resolved_)[key] = v;
  return v.get<std::string>();
}

std::string JsonNode::string(const std::string& key, const std::string& fallback) {
  if (!has(key)) {
    known_.insert(key);
    (*resolved_)[key] = fallback;
    return fallback;
  }
  return string(key);
}

std::string JsonNode::choice(const std::string& key, const std::vector<std::string>& options,
                             const std::string& fallback) {
  std::string list;
  for (size_t k = 0; k < options.size(); ++k) list += (k ? ", " : "") + ("\"" + options[k] + "\"");
  if (!has(key) && !fallback.empty()) {
    known_.insert(key);
    (*resolved_)[key] = fallback;
    return fallback;
  }
  known_.insert(key);
  const Json& v = required(key);
  if (!v.is_string()) throw SceneError(key_path(key), json_type_name(v) + " " + json_text(v), "one of " + list);
  const std::string s = v.get<std::string>();
  for (auto& o : options)
    if (s == o) {
      (*resolved_)[key] = s;
      return s;
    }
  throw SceneError(key_path(key), json_text(v), "one of " + list);
}

std::vector<double> JsonNode::vector(const std::string& key, size_t n, const Range& range) {
  known_.insert(key);
  const Json& v = required(key);
  if (!v.is_array() || v.size() != n)
    throw SceneError(key_path(key), json_type_name(v) + " " + json_text(v),
                     "an array of " + std::to_string(n) + " numbers (one per dimension)");
  std::vector<double> r;
  Json out = Json::array();
  for (size_t k = 0; k < n; ++k) {
    const std::string p = key_path(key) + "/" + std::to_string(k);
    const double x = to_number(v[k], p);
    check_range(x, range, p, v[k]);
    r.push_back(x);
    out.push_back(x);
  }
  (*resolved_)[key] = out;
  return r;
}

std::vector<double> JsonNode::vector(const std::string& key, size_t n, const std::vector<double>& fallback,
                                     const Range& range) {
  if (!has(key)) {
    known_.insert(key);
    (*resolved_)[key] = fallback;
    return fallback;
  }
  return vector(key, n, range);
}

std::string JsonNode::expression(const std::string& key, const std::string& fallback) {
  known_.insert(key);
  if (!has(key)) {
    (*resolved_)[key] = fallback;
    return fallback;
  }
  const Json& v = (*value_)[key];
  std::string s;
  if (v.is_number()) {
    std::ostringstream o;
    o.precision(17);
    o << v.get<double>();
    s = o.str();
  } else if (v.is_string()) {
    s = v.get<std::string>();
  } else {
    throw SceneError(key_path(key), json_type_name(v) + " " + json_text(v), "a number or an expression (string)");
  }
  (*resolved_)[key] = v;
  return s;
}

JsonNode JsonNode::object(const std::string& key) {
  known_.insert(key);
  const Json& v = required(key);
  return JsonNode(v, key_path(key), (*resolved_)[key], eval_);
}

std::optional<JsonNode> JsonNode::optional_object(const std::string& key) {
  known_.insert(key);
  if (!has(key)) return std::nullopt;
  return JsonNode((*value_)[key], key_path(key), (*resolved_)[key], eval_);
}

JsonNode JsonNode::object_or_empty(const std::string& key) {
  known_.insert(key);
  static const Json empty = Json::object();
  return JsonNode(has(key) ? (*value_)[key] : empty, key_path(key), (*resolved_)[key], eval_);
}

std::vector<const Json*> JsonNode::array(const std::string& key, bool needed, size_t min_size) {
  known_.insert(key);
  std::vector<const Json*> r;
  if (!has(key)) {
    if (needed) required(key);
    (*resolved_)[key] = Json::array();
    return r;
  }
  const Json& v = (*value_)[key];
  if (!v.is_array()) throw SceneError(key_path(key), json_type_name(v) + " " + json_text(v), "an array");
  if (v.size() < min_size)
    throw SceneError(key_path(key), "an array of " + std::to_string(v.size()),
                     "at least " + std::to_string(min_size) + " element(s)");
  (*resolved_)[key] = Json::array();
  for (auto& e : v) {
    r.push_back(&e);
    (*resolved_)[key].push_back(Json::object());
  }
  return r;
}

JsonNode JsonNode::element(const std::string& key, size_t index, const Json& value) {
  return JsonNode(value, key_path(key) + "/" + std::to_string(index), (*resolved_)[key][index], eval_);
}

void JsonNode::finish() {
  for (auto it = value_->begin(); it != value_->end(); ++it) {
    if (known_.count(it.key())) continue;
    std::string allowed;
    for (auto& k : known_) allowed += (allowed.empty() ? "" : ", ") + k;
    const std::string hint = nearest_name(it.key(), std::vector<std::string>(known_.begin(), known_.end()));
    throw SceneError(key_path(it.key()),
                     hint.empty() ? "an unknown key" : "an unknown key; did you mean '" + hint + "'?",
                     "one of: " + allowed);
  }
}

}  // namespace mfsd
