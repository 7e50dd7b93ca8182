#include "params.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "from_chars_real.h"

namespace accel {
namespace {

bool parse_long_strict(std::string_view s, long* out) {
  const char* end = s.data() + s.size();
  auto [ptr, ec] = std::from_chars(s.data(), end, *out);
  return !s.empty() && ec == std::errc() && ptr == end;
}

bool parse_double_strict(std::string_view s, double* out) {
  const char* end = s.data() + s.size();
  auto [ptr, ec] = from_chars_real(s.data(), end, *out);
  return !s.empty() && ec == std::errc() && ptr == end && std::isfinite(*out);
}

std::string number_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string quoted_who(const ParamSpec& spec, const std::string& structure_name) {
  return (structure_name.empty() ? "" : structure_name + " ") + "parameter '" + spec.name + "'";
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

std::string format_param_number(double v) {
  char buf[40];
  for (int precision = 6; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    double back = 0.0;
    if (parse_double_strict(buf, &back) && back == v) break;
  }
  return buf;
}

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

std::string ParamSpec::text(const ParamValue& value) const {
  switch (type) {
    case Type::Int: return std::to_string(std::get<int>(value));
    case Type::Float: return format_param_number(std::get<double>(value));
    case Type::Int3: {
      const auto& v = std::get<std::array<int, 3>>(value);
      return std::to_string(v[0]) + "," + std::to_string(v[1]) + "," + std::to_string(v[2]);
    }
    case Type::Choice: {
      const int i = std::get<int>(value);
      ACCEL_CHECK(i >= 0 && size_t(i) < choices.size());
      return choices[size_t(i)];
    }
  }
  return {};
}

Result<ParamValue> parse_param(const ParamSpec& spec, const std::string& text, const std::string& structure_name) {
  auto bad = [&] {
    return make_error(quoted_who(spec, structure_name) + " = '" + text + "' is invalid: expected " + spec.range_text());
  };
  switch (spec.type) {
    case ParamSpec::Type::Int: {
      long v;
      if (!parse_long_strict(text, &v) || v < spec.min || v > spec.max) return bad();
      return ParamValue(int(v));
    }
    case ParamSpec::Type::Float: {
      double v;
      if (!parse_double_strict(text, &v) || v < spec.min || v > spec.max) return bad();
      return ParamValue(v);
    }
    case ParamSpec::Type::Int3: {
      const auto parts = split(text, ',');
      if (parts.size() != 3) return bad();
      std::array<int, 3> out{};
      for (size_t i = 0; i < 3; ++i) {
        long v;
        if (!parse_long_strict(parts[i], &v) || v < spec.min || v > spec.max) return bad();
        out[i] = int(v);
      }
      return ParamValue(out);
    }
    case ParamSpec::Type::Choice:
      for (size_t i = 0; i < spec.choices.size(); ++i)
        if (spec.choices[i] == text) return ParamValue(int(i));
      return bad();
  }
  return bad();
}

Status validate_param(const ParamSpec& spec, const ParamValue& value, const std::string& structure_name) {
  const std::string who = quoted_who(spec, structure_name);
  auto bad = [&](const std::string& shown) {
    return make_error(who + " = '" + shown + "' is invalid: expected " + spec.range_text());
  };
  switch (spec.type) {
    case ParamSpec::Type::Int: {
      const int* v = std::get_if<int>(&value);
      if (!v) return make_error(who + " takes " + spec.range_text());
      if (*v < spec.min || *v > spec.max) return bad(std::to_string(*v));
      return {};
    }
    case ParamSpec::Type::Float: {
      const double* v = std::get_if<double>(&value);
      if (!v) return make_error(who + " takes " + spec.range_text());
      if (!std::isfinite(*v) || *v < spec.min || *v > spec.max) return bad(format_param_number(*v));
      return {};
    }
    case ParamSpec::Type::Int3: {
      const auto* v = std::get_if<std::array<int, 3>>(&value);
      if (!v) return make_error(who + " takes " + spec.range_text());
      for (int c : *v)
        if (c < spec.min || c > spec.max) return bad(spec.text(*v));
      return {};
    }
    case ParamSpec::Type::Choice: {
      const int* v = std::get_if<int>(&value);
      if (!v) return make_error(who + " takes " + spec.range_text());
      if (*v < 0 || size_t(*v) >= spec.choices.size()) return bad("choice #" + std::to_string(*v));
      return {};
    }
  }
  return make_error(who + ": unknown type");
}

ParamSet::ParamSet(std::vector<ParamSpec> specs, std::string structure_name)
    : specs_(std::move(specs)), structure_(std::move(structure_name)) {
  for (const auto& s : specs_) values_.push_back(s.default_typed);
  explicit_.assign(specs_.size(), false);
}

Result<ParamSet> ParamSet::parse(const std::vector<ParamSpec>& specs, const std::vector<std::string>& key_values,
                                 const std::string& structure_name) {
  ParamSet set(specs, structure_name);
  for (const auto& kv : key_values) {
    const size_t eq = kv.find('=');
    if (eq == std::string::npos || eq == 0)
      return make_error("parameter '" + kv + "' must be written key=value");
    auto r = set.set(kv.substr(0, eq), kv.substr(eq + 1));
    if (!r) return r.error();
  }
  return set;
}

int ParamSet::index_of(const std::string& key) const {
  for (size_t i = 0; i < specs_.size(); ++i)
    if (specs_[i].name == key) return int(i);
  return -1;
}

int ParamSet::checked_index(const std::string& key) const {
  const int i = index_of(key);
  ACCEL_CHECK(i >= 0);  // asking for a parameter the structure does not declare is a bug
  return i;
}

Status ParamSet::set(const std::string& key, const std::string& text) {
  const int i = index_of(key);
  if (i < 0) {
    std::string valid;
    for (const auto& s : specs_) valid += (valid.empty() ? "" : ", ") + s.name;
    const std::string who = structure_.empty() ? "this structure" : "structure '" + structure_ + "'";
    return make_error("unknown parameter '" + key + "' for " + who + " (valid: " +
                      (valid.empty() ? "none" : valid) + ")");
  }
  auto parsed = parse_param(specs_[size_t(i)], text, structure_);
  if (!parsed) return parsed.error();
  values_[size_t(i)] = parsed.value();
  explicit_[size_t(i)] = true;
  return {};
}

Status ParamSet::set_value(const std::string& key, const ParamValue& value) {
  const int i = index_of(key);
  if (i < 0) return make_error("unknown parameter '" + key + "'");
  auto ok = validate_param(specs_[size_t(i)], value, structure_);
  if (!ok) return ok;
  values_[size_t(i)] = value;
  explicit_[size_t(i)] = true;
  return {};
}

void ParamSet::reset(const std::string& key) {
  const int i = checked_index(key);
  values_[size_t(i)] = specs_[size_t(i)].default_for(planar_);
  explicit_[size_t(i)] = false;
}

void ParamSet::set_planar(bool planar) {
  planar_ = planar;
  for (size_t i = 0; i < specs_.size(); ++i)
    if (!explicit_[i]) values_[i] = specs_[i].default_for(planar);
}

const ParamValue& ParamSet::value(const std::string& key) const { return values_[size_t(checked_index(key))]; }

int ParamSet::get_int(const std::string& key) const {
  const int i = checked_index(key);
  ACCEL_CHECK(specs_[size_t(i)].type == ParamSpec::Type::Int);
  return std::get<int>(values_[size_t(i)]);
}

double ParamSet::get_float(const std::string& key) const {
  const int i = checked_index(key);
  ACCEL_CHECK(specs_[size_t(i)].type == ParamSpec::Type::Float);
  return std::get<double>(values_[size_t(i)]);
}

int ParamSet::get_choice_index(const std::string& key) const {
  const int i = checked_index(key);
  ACCEL_CHECK(specs_[size_t(i)].type == ParamSpec::Type::Choice);
  return std::get<int>(values_[size_t(i)]);
}

const std::string& ParamSet::get_choice(const std::string& key) const {
  const int i = checked_index(key);
  return specs_[size_t(i)].choices[size_t(get_choice_index(key))];
}

std::array<int, 3> ParamSet::get_int3(const std::string& key) const {
  const int i = checked_index(key);
  ACCEL_CHECK(specs_[size_t(i)].type == ParamSpec::Type::Int3);
  return std::get<std::array<int, 3>>(values_[size_t(i)]);
}

std::string ParamSet::text(const std::string& key) const {
  const int i = checked_index(key);
  return specs_[size_t(i)].text(values_[size_t(i)]);
}

bool ParamSet::is_set(const std::string& key) const { return explicit_[size_t(checked_index(key))]; }

std::vector<std::string> ParamSet::explicit_key_values() const {
  std::vector<std::string> out;
  for (size_t i = 0; i < specs_.size(); ++i)
    if (explicit_[i]) out.push_back(specs_[i].name + "=" + specs_[i].text(values_[i]));
  return out;
}

std::string ParamSet::to_string() const {
  std::string s;
  for (const std::string& kv : explicit_key_values()) s += (s.empty() ? "" : ",") + kv;
  return s;
}

std::string ParamSet::to_string_all() const {
  std::string s;
  for (size_t i = 0; i < specs_.size(); ++i)
    s += (s.empty() ? "" : " ") + specs_[i].name + "=" + specs_[i].text(values_[i]);
  return s;
}

std::vector<std::string> with_param(std::vector<std::string> params, const std::string& key, const std::string& value) {
  const std::string prefix = key + "=";
  for (std::string& p : params) {
    if (p.starts_with(prefix)) {
      p = prefix + value;
      return params;
    }
  }
  params.push_back(prefix + value);
  return params;
}

std::string param_value(const std::vector<std::string>& params, const std::string& key, const std::string& fallback) {
  const std::string prefix = key + "=";
  for (const std::string& p : params)
    if (p.starts_with(prefix)) return p.substr(prefix.size());
  return fallback;
}

}  // namespace accel
