#include "params.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace accel {
namespace {

bool parse_long_strict(std::string_view s, long* out) {
  const char* end = s.data() + s.size();
  auto [ptr, ec] = std::from_chars(s.data(), end, *out);
  return !s.empty() && ec == std::errc() && ptr == end;
}

bool parse_double_strict(std::string_view s, double* out) {
  const char* end = s.data() + s.size();
  auto [ptr, ec] = std::from_chars(s.data(), end, *out);
  return !s.empty() && ec == std::errc() && ptr == end && std::isfinite(*out);
}

std::string number_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::vector<std::string_view> split(std::string_view s, char sep) {
  std::vector<std::string_view> parts;
  size_t start = 0;
  while (true) {
    const size_t pos = s.find(sep, start);
    parts.push_back(s.substr(start, pos == std::string_view::npos ? std::string_view::npos : pos - start));
    if (pos == std::string_view::npos) break;
    start = pos + 1;
  }
  return parts;
}

}  // namespace

std::string ParamSpec::range_text() const {
  switch (type) {
    case Type::Int: return "an integer in [" + number_text(min) + ", " + number_text(max) + "]";
    case Type::Float: return "a number in [" + number_text(min) + ", " + number_text(max) + "]";
    case Type::Int3:
      return "three integers NX,NY,NZ each in [" + number_text(min) + ", " + number_text(max) + "]";
    case Type::Choice: {
      std::string s = "one of: ";
      for (size_t i = 0; i < choices.size(); ++i) s += (i ? ", " : "") + choices[i];
      return s;
    }
  }
  return {};
}

Status validate_param(const ParamSpec& spec, const std::string& value, const std::string& structure_name) {
  const std::string who = (structure_name.empty() ? "" : structure_name + " ") + "parameter '" + spec.name + "'";
  auto bad = [&] { return make_error(who + " = '" + value + "' is invalid: expected " + spec.range_text()); };
  switch (spec.type) {
    case ParamSpec::Type::Int: {
      long v;
      if (!parse_long_strict(value, &v) || v < spec.min || v > spec.max) return bad();
      return {};
    }
    case ParamSpec::Type::Float: {
      double v;
      if (!parse_double_strict(value, &v) || v < spec.min || v > spec.max) return bad();
      return {};
    }
    case ParamSpec::Type::Int3: {
      const auto parts = split(value, ',');
      if (parts.size() != 3) return bad();
      for (auto p : parts) {
        long v;
        if (!parse_long_strict(p, &v) || v < spec.min || v > spec.max) return bad();
      }
      return {};
    }
    case ParamSpec::Type::Choice:
      for (const auto& c : spec.choices)
        if (c == value) return {};
      return bad();
  }
  return bad();
}

Result<ParamSet> ParamSet::parse(const std::vector<ParamSpec>& specs, const std::vector<std::string>& key_values,
                                 const std::string& structure_name) {
  ParamSet set;
  set.specs_ = specs;
  set.structure_ = structure_name;
  for (const auto& s : specs) set.values_[s.name] = s.default_value;
  for (const auto& kv : key_values) {
    const size_t eq = kv.find('=');
    if (eq == std::string::npos || eq == 0)
      return make_error("parameter '" + kv + "' must be written key=value");
    auto r = set.set(kv.substr(0, eq), kv.substr(eq + 1));
    if (!r) return r.error();
  }
  return set;
}

Status ParamSet::set(const std::string& key, const std::string& value) {
  const ParamSpec* spec = find(key);
  if (!spec) {
    std::string valid;
    for (const auto& s : specs_) valid += (valid.empty() ? "" : ", ") + s.name;
    const std::string who = structure_.empty() ? "this structure" : "structure '" + structure_ + "'";
    return make_error("unknown parameter '" + key + "' for " + who + " (valid: " +
                      (valid.empty() ? "none" : valid) + ")");
  }
  auto ok = validate_param(*spec, value, structure_);
  if (!ok) return ok.error();
  values_[key] = value;
  explicit_[key] = true;
  return {};
}

const ParamSpec* ParamSet::find(const std::string& key) const {
  for (const auto& s : specs_)
    if (s.name == key) return &s;
  return nullptr;
}

const std::string& ParamSet::get_string(const std::string& key) const {
  auto it = values_.find(key);
  ACCEL_CHECK(it != values_.end());
  return it->second;
}

int ParamSet::get_int(const std::string& key) const {
  long v = 0;
  ACCEL_CHECK(parse_long_strict(get_string(key), &v));
  return int(v);
}

double ParamSet::get_float(const std::string& key) const {
  double v = 0;
  ACCEL_CHECK(parse_double_strict(get_string(key), &v));
  return v;
}

const std::string& ParamSet::get_choice(const std::string& key) const { return get_string(key); }

std::array<int, 3> ParamSet::get_int3(const std::string& key) const {
  const auto parts = split(get_string(key), ',');
  ACCEL_CHECK(parts.size() == 3);
  std::array<int, 3> out{};
  for (int i = 0; i < 3; ++i) {
    long v = 0;
    ACCEL_CHECK(parse_long_strict(parts[i], &v));
    out[i] = int(v);
  }
  return out;
}

bool ParamSet::is_set(const std::string& key) const { return explicit_.count(key) != 0; }

std::string ParamSet::to_string() const {
  std::string s;
  for (const auto& spec : specs_)
    if (is_set(spec.name)) s += (s.empty() ? "" : ",") + spec.name + "=" + get_string(spec.name);
  return s;
}

std::string ParamSet::to_string_all() const {
  std::string s;
  for (const auto& spec : specs_) s += (s.empty() ? "" : " ") + spec.name + "=" + get_string(spec.name);
  return s;
}

}  // namespace accel
