// Typed, validated access to one JSON object of a scene file. Every getter
// names the JSON path in its error, records the resolved value (defaults
// included) into the resolved scene written to run.json, and marks the key as
// known; finish() rejects unknown keys. Numbers may be given as expressions of
// the scene's constants ("H/40").
#pragma once
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace mfsd {

using Json = nlohmann::ordered_json;

struct Range {
  double lo = -1e308, hi = 1e308;
  bool lo_open = false, hi_open = false;
  std::string text;  // e.g. "a number in (0, 1]"
  bool contains(double x) const { return (lo_open ? x > lo : x >= lo) && (hi_open ? x < hi : x <= hi); }
  static Range positive() { return {0, 1e308, true, false, "a positive number"}; }
  static Range non_negative() { return {0, 1e308, false, false, "a number >= 0"}; }
  static Range any() { return {-1e308, 1e308, false, false, "a number"}; }
};

class JsonNode {
 public:
  // `constants` evaluates string numbers; may be empty (then strings are errors).
  using ConstantEvaluator = std::function<double(const std::string& expr, const std::string& path)>;

  JsonNode(const Json& value, std::string path, Json& resolved, ConstantEvaluator eval);

  const std::string& path() const { return path_; }
  bool has(const std::string& key) const;
  std::string key_path(const std::string& key) const { return path_ + "/" + key; }

  double number(const std::string& key, const Range& range);                   // required
  double number(const std::string& key, double fallback, const Range& range);  // optional
  long integer(const std::string& key, long fallback, long lo, long hi);
  bool boolean(const std::string& key, bool fallback);
  std::string string(const std::string& key);  // required, non-empty
  std::string string(const std::string& key, const std::string& fallback);
  std::string choice(const std::string& key, const std::vector<std::string>& options, const std::string& fallback = "");
  // Fixed-length array of numbers (length `n`).
  std::vector<double> vector(const std::string& key, size_t n, const Range& range);
  std::vector<double> vector(const std::string& key, size_t n, const std::vector<double>& fallback, const Range& range);
  // A string or a number kept as an expression source (e.g. initial velocity).
  std::string expression(const std::string& key, const std::string& fallback);

  JsonNode object(const std::string& key);  // required object
  std::optional<JsonNode> optional_object(const std::string& key);
  // The object at key, or an empty one (all defaults) when absent.
  JsonNode object_or_empty(const std::string& key);
  // Required array; each element's path is key/index.
  std::vector<const Json*> array(const std::string& key, bool required, size_t min_size = 0);
  JsonNode element(const std::string& key, size_t index, const Json& value);

  void finish();  // unknown keys are errors naming the allowed ones

  // Shared evaluator for nested nodes.
  const ConstantEvaluator& evaluator() const { return eval_; }
  Json& resolved() { return *resolved_; }

 private:
  const Json& required(const std::string& key) const;
  double to_number(const Json& v, const std::string& path) const;

  const Json* value_;
  std::string path_;
  Json* resolved_;
  ConstantEvaluator eval_;
  std::set<std::string> known_;
};

// Short JSON text of a value for error messages.
std::string json_text(const Json& v);
std::string json_type_name(const Json& v);

}  // namespace mfsd
