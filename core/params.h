#pragma once
// Structure parameters (`--param key=value` on the CLI, widgets in the viewer). Each
// parameter carries its documentation, default and valid range, so the CLI's error
// message, the viewer's clamping and its tooltip all say the same thing.
#include <array>
#include <map>
#include <string>
#include <vector>

#include "result.h"

namespace accel {

/// One parameter a structure accepts.
struct ParamSpec {
  enum class Type { Int, Float, Choice, Int3 };
  std::string name;                  ///< as typed after --param, e.g. "leaf_size"
  Type type = Type::Int;
  std::string default_value;         ///< in the same syntax as the CLI takes it
  double min = 0.0, max = 0.0;       ///< inclusive range (Int, Float, each Int3 component)
  std::vector<std::string> choices;  ///< the valid values (Choice)
  std::string doc;                   ///< one sentence, shown in help texts and tooltips
  /// "an integer in [1, 64]", "one of: bbox, exact", ...: used in error messages.
  std::string range_text() const;
};

/// Validated parameter values of one structure: every spec'd name has a value.
class ParamSet {
 public:
  ParamSet() = default;
  /// Defaults for every spec, overridden by `key=value` strings. Errors name the key and
  /// the valid range, or list the valid keys for an unknown one.
  static Result<ParamSet> parse(const std::vector<ParamSpec>& specs, const std::vector<std::string>& key_values,
                                const std::string& structure_name = {});
  /// Sets one value (validated). Used by the viewer's widgets.
  Status set(const std::string& key, const std::string& value);

  int get_int(const std::string& key) const;
  double get_float(const std::string& key) const;
  const std::string& get_choice(const std::string& key) const;
  std::array<int, 3> get_int3(const std::string& key) const;
  const std::string& get_string(const std::string& key) const;
  /// True when the user gave this key explicitly (not its default).
  bool is_set(const std::string& key) const;
  const std::vector<ParamSpec>& specs() const { return specs_; }
  /// "key=value,key=value" of the explicitly set keys, in spec order ("" when all default).
  std::string to_string() const;
  /// "key=value ..." of every key, for stats output.
  std::string to_string_all() const;

 private:
  const ParamSpec* find(const std::string& key) const;
  std::vector<ParamSpec> specs_;
  std::string structure_;
  std::map<std::string, std::string> values_;
  std::map<std::string, bool> explicit_;
};

/// Validates `value` against `spec`; error message names the parameter and its range.
Status validate_param(const ParamSpec& spec, const std::string& value, const std::string& structure_name = {});

}  // namespace accel
