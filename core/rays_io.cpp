#include "rays_io.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace accel {

bool parse_ray_number(std::string_view token, float* out) {
  bool negative = false;
  if (!token.empty() && (token[0] == '+' || token[0] == '-')) {
    negative = token[0] == '-';
    token.remove_prefix(1);
  }
  if (token.empty() || token[0] == '+' || token[0] == '-') return false;
  auto format = std::chars_format::general;
  if (token.size() > 2 && token[0] == '0' && (token[1] == 'x' || token[1] == 'X')) {
    token.remove_prefix(2);  // from_chars' hex format takes the digits without "0x"
    format = std::chars_format::hex;
  }
  float value;
  const char* end = token.data() + token.size();
  auto [ptr, ec] = std::from_chars(token.data(), end, value, format);
  if (ec != std::errc() || ptr != end) return false;
  *out = negative ? -value : value;
  return true;
}

Result<std::vector<Ray>> parse_rays(const std::string& text, const std::string& source_name) {
  std::vector<Ray> rays;
  std::istringstream in(text);
  std::string line;
  size_t line_no = 0;
  auto fail = [&](const std::string& what) {
    return make_error(source_name + ":" + std::to_string(line_no) + ": " + what);
  };
  while (std::getline(in, line)) {
    ++line_no;
    std::vector<std::string_view> tok;
    {
      std::string_view s(line);
      size_t i = 0;
      while (i < s.size()) {
        while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
        size_t j = i;
        while (j < s.size() && !std::isspace(static_cast<unsigned char>(s[j]))) ++j;
        if (j > i) tok.push_back(s.substr(i, j - i));
        i = j;
      }
    }
    if (tok.empty() || tok[0][0] == '#') continue;
    if (tok.size() != 6 && tok.size() != 8)
      return fail("expected 6 or 8 numbers (ox oy oz dx dy dz [tmin tmax]), got " + std::to_string(tok.size()));
    float v[8] = {0, 0, 0, 0, 0, 0, 0, kInf};
    for (size_t k = 0; k < tok.size(); ++k) {
      if (!parse_ray_number(tok[k], &v[k]))
        return fail("malformed number '" + std::string(tok[k]) + "' (field " + std::to_string(k + 1) + ")");
      if (std::isnan(v[k])) return fail("NaN in field " + std::to_string(k + 1));
      if (k < 6 && std::isinf(v[k]))
        return fail("origin and direction must be finite (field " + std::to_string(k + 1) + " is '" +
                    std::string(tok[k]) + "')");
    }
    if (v[3] == 0.0f && v[4] == 0.0f && v[5] == 0.0f) return fail("direction is the zero vector");
    if (v[6] == kInf) return fail("tmin is +inf");
    if (v[7] == -kInf) return fail("tmax is -inf");
    Ray r;
    r.org = Vec3(v[0], v[1], v[2]);
    r.dir = Vec3(v[3], v[4], v[5]);
    r.tmin = v[6];
    r.tmax = v[7];
    rays.push_back(r);
  }
  return rays;
}

Result<std::vector<Ray>> read_rays(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return make_error(path + ": cannot open rays file for reading");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return parse_rays(buffer.str(), path);
}

std::string format_hit_row(size_t ray_index, const Hit& hit) {
  char buf[128];
  if (!hit.valid()) {
    std::snprintf(buf, sizeof buf, "%zu,-1,inf,0,0\n", ray_index);
  } else {
    std::snprintf(buf, sizeof buf, "%zu,%d,%.9g,%.9g,%.9g\n", ray_index, hit.prim, double(hit.t), double(hit.u),
                  double(hit.v));
  }
  return buf;
}

Status write_file_atomic(const std::string& path, const std::string& content) {
  const std::string tmp = path + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) return make_error(path + ": cannot open for writing");
    out.write(content.data(), std::streamsize(content.size()));
    out.flush();
    if (!out) {
      std::remove(tmp.c_str());
      return make_error(path + ": write failed (disk full?)");
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    return make_error(path + ": cannot replace the output file");
  }
  return {};
}

Status write_hits_csv(const std::string& path, const std::vector<Hit>& hits) {
  std::string content = "ray,prim,t,u,v\n";
  content.reserve(content.size() + hits.size() * 40);
  for (size_t i = 0; i < hits.size(); ++i) content += format_hit_row(i, hits[i]);
  return write_file_atomic(path, content);
}

}  // namespace accel
