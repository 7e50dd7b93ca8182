#pragma once
// Structure parameters (`--param key=value` on the CLI, widgets in the viewer), declared
// once per structure in a ParamTable that binds each name to its options-struct field,
// range, documentation and, for choices, the enum table. The default is the field's value in
// a default-constructed options struct. The CLI's error messages, `accelviz-cli params` and
// the viewer's widgets and tooltips all read the ParamSpecs the table makes; parsed values
// are stored typed, so an unknown or out-of-range value cannot reach a builder.
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "result.h"

namespace accel {

/// A typed parameter value: Int -> int, Float -> double, Choice -> the index into
/// ParamSpec::choices (an int), Int3 -> three ints.
using ParamValue = std::variant<int, double, std::array<int, 3>>;

/// One parameter a structure accepts, as the front ends see it.
struct ParamSpec {
  enum class Type { Int, Float, Choice, Int3 };
  std::string name;                  ///< as typed after --param, e.g. "leaf_size"
  Type type = Type::Int;
  std::string default_value;         ///< the default as text, in the syntax the CLI takes
  double min = 0.0, max = 0.0;       ///< inclusive range (Int, Float, each Int3 component)
  std::vector<std::string> choices;  ///< the valid values (Choice)
  std::string doc;                   ///< one sentence, shown in help texts and tooltips
  ParamValue default_typed;          ///< the default, typed
  /// The default over a 2D scene (Scene::planar(), the blackboard) where it differs from
  /// default_typed: the lecture's 2D figure instead of the 3D cost model's choice (the
  /// octree's max_prims=1, ct=0). Unset: default_typed in 2D too.
  std::optional<ParamValue> planar_default;
  /// The default over a 2D scene (`planar`) or a 3D one.
  const ParamValue& default_for(bool planar) const {
    return planar && planar_default ? *planar_default : default_typed;
  }
  /// "an integer in [1, 64]", "one of: bbox, exact", ...: used in error messages.
  std::string range_text() const;
  /// `value` (of this spec's type) as the CLI would take it: "2", "0.25", "16,16,16", "sah".
  std::string text(const ParamValue& value) const;
};

/// Validated, typed parameter values of one structure: every spec'd name has a value.
class ParamSet {
 public:
  ParamSet() = default;
  /// Every spec at its default.
  explicit ParamSet(std::vector<ParamSpec> specs, std::string structure_name = {});
  /// Defaults for every spec, overridden by `key=value` strings. Errors name the key and
  /// the valid range, or list the valid keys for an unknown one.
  static Result<ParamSet> parse(const std::vector<ParamSpec>& specs, const std::vector<std::string>& key_values,
                                const std::string& structure_name = {});
  /// Sets one value from its text (validated), as the CLI gives it.
  Status set(const std::string& key, const std::string& text);
  /// Sets one typed value (validated: type, range, choice index), as the viewer's widgets do.
  Status set_value(const std::string& key, const ParamValue& value);
  /// Puts `key` back to its default (no longer explicitly set).
  void reset(const std::string& key);
  /// The defaults of a 2D scene (ParamSpec::planar_default) for every key not set explicitly
  /// (true), or the 3D ones (false, as constructed). Structure::build sets it from the scene.
  void set_planar(bool planar);
  /// Whether the keys not set explicitly hold a 2D scene's defaults.
  bool planar() const { return planar_; }

  /// The typed value of `key` (which must be a spec'd name).
  const ParamValue& value(const std::string& key) const;
  int get_int(const std::string& key) const;
  double get_float(const std::string& key) const;
  /// A choice's index into its spec's choices, and its text.
  int get_choice_index(const std::string& key) const;
  const std::string& get_choice(const std::string& key) const;
  std::array<int, 3> get_int3(const std::string& key) const;
  /// The value of `key` as text ("2", "sah", "16,16,16").
  std::string text(const std::string& key) const;
  /// True when the user gave this key explicitly (not its default).
  bool is_set(const std::string& key) const;
  /// True when `key` is one of the spec'd names.
  bool has(const std::string& key) const { return index_of(key) >= 0; }
  const std::vector<ParamSpec>& specs() const { return specs_; }
  const std::string& structure_name() const { return structure_; }
  /// "key=value,key=value" of the explicitly set keys, in spec order ("" when all default).
  std::string to_string() const;
  /// "key=value ..." of every key, for stats output.
  std::string to_string_all() const;
  /// The explicitly set keys as "key=value" strings, in spec order (parse() takes them back).
  std::vector<std::string> explicit_key_values() const;
  /// Same values and the same keys explicitly set.
  bool operator==(const ParamSet& other) const {
    return structure_ == other.structure_ && values_ == other.values_ && explicit_ == other.explicit_ &&
           planar_ == other.planar_;
  }

 private:
  int index_of(const std::string& key) const;
  int checked_index(const std::string& key) const;
  std::vector<ParamSpec> specs_;
  std::string structure_;
  std::vector<ParamValue> values_;  // per spec
  std::vector<bool> explicit_;      // per spec: given by the user
  bool planar_ = false;             // the keys not given hold a 2D scene's defaults
};

/// Parses and validates `text` against `spec`; the error names the parameter and its range.
Result<ParamValue> parse_param(const ParamSpec& spec, const std::string& text, const std::string& structure_name = {});
/// Validates a typed value against `spec` (type, range, choice index).
Status validate_param(const ParamSpec& spec, const ParamValue& value, const std::string& structure_name = {});
/// Shortest "%g"-style text that reads back as exactly `v` ("2", "0.2", "1000").
std::string format_param_number(double v);

/// Replaces `key`'s value in a `key=value` list (appends it when absent): a front end's
/// variation of a structure's parameters (the viewer's comparison and sweep).
std::vector<std::string> with_param(std::vector<std::string> params, const std::string& key, const std::string& value);
/// The value of `key` in a `key=value` list, or `fallback`.
std::string param_value(const std::vector<std::string>& params, const std::string& key,
                        const std::string& fallback = "");

/// The one declaration of a structure's parameters over its options struct `Options`.
/// Each entry binds a name to a field, given as a member pointer or as a callable that
/// returns a reference to the field (`[](Options& o) -> auto& { return o.build.leaf_size; }`);
/// the default is that field in `Options{}`, and over a 2D scene that field in the
/// `planar_defaults` the table was made with, where it differs (ParamSpec::planar_default).
/// specs() feeds the registry (CLI, viewer), apply() turns a validated ParamSet of these
/// specs into the options struct.
template <class Options>
class ParamTable {
 public:
  /// The same defaults in 2D and 3D.
  ParamTable() = default;
  /// A 2D scene's defaults from `planar_defaults` (an Options whose fields differ from
  /// `Options{}` where the blackboard wants other defaults).
  explicit ParamTable(const Options& planar_defaults) : planar_(planar_defaults) {}

  /// An integer field (any integral type) in [min, max].
  template <class Field>
  ParamTable& integer(std::string name, Field field, int min, int max, std::string doc) {
    const int def = int(std::invoke(field, defaults()));
    add(ParamSpec::Type::Int, std::move(name), ParamValue(def), planar_value<int>(field), min, max, {}, std::move(doc),
        [field](Options& o, const ParamSet& s, const std::string& key) {
          auto& f = std::invoke(field, o);
          f = static_cast<std::remove_reference_t<decltype(f)>>(s.get_int(key));
        });
    return *this;
  }
  /// A floating-point field (float or double) in [min, max].
  template <class Field>
  ParamTable& number(std::string name, Field field, double min, double max, std::string doc) {
    const double def = double(std::invoke(field, defaults()));
    add(ParamSpec::Type::Float, std::move(name), ParamValue(def), planar_value<double>(field), min, max, {},
        std::move(doc),
        [field](Options& o, const ParamSet& s, const std::string& key) {
          auto& f = std::invoke(field, o);
          f = static_cast<std::remove_reference_t<decltype(f)>>(s.get_float(key));
        });
    return *this;
  }
  /// A field of enum (or bool, int) type E, one of the named values of `table`.
  template <class Field, class E>
  ParamTable& choice(std::string name, Field field, std::vector<std::pair<std::string, E>> table, std::string doc) {
    const E def = std::invoke(field, defaults());
    int def_index = -1, planar_index = -1;
    std::vector<std::string> names;
    for (size_t i = 0; i < table.size(); ++i) {
      names.push_back(table[i].first);
      if (table[i].second == def) def_index = int(i);
      if (planar_ && table[i].second == planar_field(field)) planar_index = int(i);
    }
    ACCEL_CHECK(def_index >= 0);  // the options struct's default must be one of the choices
    ACCEL_CHECK(!planar_ || planar_index >= 0);
    add(ParamSpec::Type::Choice, std::move(name), ParamValue(def_index),
        planar_index >= 0 ? std::optional<ParamValue>(planar_index) : std::nullopt, 0, 0, std::move(names),
        std::move(doc),
        [field, table = std::move(table)](Options& o, const ParamSet& s, const std::string& key) {
          std::invoke(field, o) = table[size_t(s.get_choice_index(key))].second;
        });
    return *this;
  }
  /// A field of type std::array<int, 3>, each component in [min, max] (whether the user
  /// gave it is ParamSet::is_set).
  template <class Field>
  ParamTable& int3(std::string name, Field field, int min, int max, std::string doc) {
    const std::array<int, 3> def = std::invoke(field, defaults());
    add(ParamSpec::Type::Int3, std::move(name), ParamValue(def), planar_value<std::array<int, 3>>(field), min, max, {},
        std::move(doc),
        [field](Options& o, const ParamSet& s, const std::string& key) { std::invoke(field, o) = s.get_int3(key); });
    return *this;
  }

  /// The declared parameters, in declaration order.
  const std::vector<ParamSpec>& specs() const { return specs_; }
  /// `Options{}` with every declared field set from `set`, whose specs must be this table's.
  Options apply(const ParamSet& set) const {
    Options o{};
    for (size_t i = 0; i < specs_.size(); ++i) {
      ACCEL_CHECK(set.has(specs_[i].name));
      setters_[i](o, set, specs_[i].name);
    }
    return o;
  }

 private:
  using Setter = std::function<void(Options&, const ParamSet&, const std::string&)>;
  static Options& defaults() {
    static Options d{};
    return d;
  }
  /// The field's value in the 2D defaults as a T, when there are 2D defaults.
  template <class T, class Field>
  std::optional<ParamValue> planar_value(Field field) const {
    if (!planar_) return std::nullopt;
    return ParamValue(T(planar_field(field)));
  }
  /// The field's value in the 2D defaults, by value (a field's accessor takes an Options&).
  template <class Field>
  auto planar_field(Field field) const {
    Options o = *planar_;
    return std::invoke(field, o);
  }
  void add(ParamSpec::Type type, std::string name, ParamValue def, std::optional<ParamValue> planar_def, double min,
           double max, std::vector<std::string> choices, std::string doc, Setter setter) {
    ParamSpec spec;
    spec.name = std::move(name);
    spec.type = type;
    spec.min = min;
    spec.max = max;
    spec.choices = std::move(choices);
    spec.doc = std::move(doc);
    spec.default_typed = def;
    spec.default_value = spec.text(def);
    ACCEL_CHECK(validate_param(spec, def).ok());  // a default outside its own range is a bug
    if (planar_def && *planar_def != def) {
      ACCEL_CHECK(validate_param(spec, *planar_def).ok());
      spec.planar_default = std::move(planar_def);
    }
    specs_.push_back(std::move(spec));
    setters_.push_back(std::move(setter));
  }
  std::optional<Options> planar_;  // a 2D scene's defaults, if they differ
  std::vector<ParamSpec> specs_;
  std::vector<Setter> setters_;
};

}  // namespace accel
