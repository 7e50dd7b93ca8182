// OBJ loading: tinyobjloader does the parsing; a strict line-by-line validation pass in front
// of it supplies what tinyobjloader does not check (number syntax, NaN/inf, index ranges,
// UTF-16 input) together with the line number every error message must name.
#include <array>
#include <charconv>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <tiny_obj_loader.h>

#include "from_chars_real.h"
#include "scene.h"
#include "yield_point.h"

namespace accel {
namespace {

/// tinyobjloader keeps a polygon's vertex count in an unsigned char.
constexpr size_t kMaxPolygonVertices = 255;

std::vector<std::string_view> split_tokens(std::string_view line) {
  std::vector<std::string_view> tokens;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != '\r') ++j;
    if (j > i) tokens.push_back(line.substr(i, j - i));
    i = j;
  }
  return tokens;
}

/// Strict decimal number: the whole token must parse (so "3.1+e2" is rejected).
bool parse_number(std::string_view token, double* out) {
  if (!token.empty() && token[0] == '+') token.remove_prefix(1);  // from_chars rejects a leading '+'
  if (token.empty() || token[0] == '+' ) return false;
  const char* end = token.data() + token.size();
  auto [ptr, ec] = from_chars_real(token.data(), end, *out, std::chars_format::general);
  return ec == std::errc() && ptr == end;
}

bool parse_int(std::string_view token, long* out) {
  if (!token.empty() && token[0] == '+') token.remove_prefix(1);
  const char* end = token.data() + token.size();
  auto [ptr, ec] = std::from_chars(token.data(), end, *out);
  return !token.empty() && ec == std::errc() && ptr == end;
}

/// What the validation pass learns besides errors: the resolved first two vertex indices of
/// every face, so tinyobjloader's output can be checked against file order.
struct ValidatedObj {
  size_t vertex_count = 0;
  std::vector<std::array<uint32_t, 2>> face_heads;
  size_t triangle_count = 0;
};

Result<ValidatedObj> validate_obj(const std::string& path, const std::string& text) {
  auto fail = [&](size_t line, const std::string& what) {
    return make_error(path + ":" + std::to_string(line) + ": " + what);
  };
  if (text.size() >= 2 && ((uint8_t(text[0]) == 0xFE && uint8_t(text[1]) == 0xFF) ||
                           (uint8_t(text[0]) == 0xFF && uint8_t(text[1]) == 0xFE)))
    return fail(1, "not a text file: UTF-16 byte order mark (save the OBJ as ASCII/UTF-8)");

  // Split into lines once; both passes walk them.
  std::vector<std::string_view> lines;
  {
    std::string_view all(text);
    size_t start = 0;
    while (start <= all.size()) {
      size_t nl = all.find('\n', start);
      if (nl == std::string_view::npos) nl = all.size();
      lines.push_back(all.substr(start, nl - start));
      start = nl + 1;
    }
  }

  ValidatedObj out;
  // Pass 1: vertices (syntax, finiteness) and NUL bytes.
  for (size_t i = 0; i < lines.size(); ++i) {
    if (i % 4096 == 0) par::yield();
    if (lines[i].find('\0') != std::string_view::npos)
      return fail(i + 1, "not a text file: contains NUL bytes (UTF-16 or binary?)");
    const auto tok = split_tokens(lines[i]);
    if (tok.empty() || tok[0] != "v") continue;
    if (tok.size() < 4) return fail(i + 1, "vertex needs 3 coordinates, got " + std::to_string(tok.size() - 1));
    for (size_t k = 1; k < tok.size(); ++k) {
      double value;
      if (!parse_number(tok[k], &value))
        return fail(i + 1, "malformed number '" + printable(tok[k]) + "' in vertex");
      if (k <= 3 && !std::isfinite(value))
        return fail(i + 1, "vertex coordinate '" + printable(tok[k]) + "' is not finite");
      if (k <= 3 && std::isinf(float(value)))
        return fail(i + 1, "vertex coordinate '" + printable(tok[k]) + "' overflows float");
    }
    ++out.vertex_count;
  }
  // Pass 2: faces. Positive indices count from 1 over the whole file; negative ones are
  // relative to the vertices read so far (OBJ spec).
  size_t vertices_so_far = 0;
  for (size_t i = 0; i < lines.size(); ++i) {
    if (i % 4096 == 0) par::yield();  // a long file in the page: the frames go on meanwhile
    const auto tok = split_tokens(lines[i]);
    if (tok.empty()) continue;
    if (tok[0] == "v") { ++vertices_so_far; continue; }
    if (tok[0] != "f") continue;
    const size_t corners = tok.size() - 1;
    if (corners < 3) return fail(i + 1, "face needs at least 3 vertices, got " + std::to_string(corners));
    if (corners > kMaxPolygonVertices)
      return fail(i + 1, "polygon with " + std::to_string(corners) + " vertices (at most 255 supported)");
    std::array<uint32_t, 2> head{};
    for (size_t k = 1; k < tok.size(); ++k) {
      const std::string_view v = tok[k].substr(0, tok[k].find('/'));
      long index = 0;
      if (!parse_int(v, &index)) return fail(i + 1, "malformed face index '" + printable(tok[k]) + "'");
      long resolved = index > 0 ? index - 1 : long(vertices_so_far) + index;
      if (index == 0) return fail(i + 1, "face index 0 is invalid (OBJ indices start at 1)");
      if (index > 0 && size_t(index) > out.vertex_count)
        return fail(i + 1, "face index " + std::to_string(index) + " out of range (file has " +
                               std::to_string(out.vertex_count) + " vertices)");
      if (resolved < 0)
        return fail(i + 1, "relative face index " + std::to_string(index) + " points before the first vertex");
      if (k <= 2) head[k - 1] = uint32_t(resolved);
    }
    out.face_heads.push_back(head);
    out.triangle_count += corners - 2;
  }
  if (out.triangle_count == 0) return fail(lines.size(), "no triangles (no 'f' faces) in the file");
  return out;
}

}  // namespace

Result<Scene> load_obj(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return make_error(path + ": cannot open file for reading: Is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) return make_error(path + ": cannot open file for reading");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) return make_error(path + ": read error");
  const std::string text = buffer.str();
  if (text.empty()) return make_error(path + ":1: empty file, no triangles");

  Result<ValidatedObj> validated = validate_obj(path, text);
  if (!validated) return validated.error();
  const ValidatedObj& info = validated.value();

  // Materials are ignored: parsing from a string never opens the .mtl file.
  tinyobj::ObjReaderConfig config;
  config.triangulate = false;  // docs/hits.md wants fan triangulation in place, done below
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromString(text, "", config)) {
    std::string msg = reader.Error();
    while (!msg.empty() && (msg.back() == '\n' || msg.back() == '\r')) msg.pop_back();
    for (char& c : msg) if (c == '\n') c = ' ';
    return make_error(path + ": " + printable(msg, 300));  // it may quote the input
  }

  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  if (attrib.vertices.size() != 3 * info.vertex_count)
    return make_error(path + ": internal: tinyobjloader read " + std::to_string(attrib.vertices.size() / 3) +
                      " vertices, validation counted " + std::to_string(info.vertex_count));
  std::vector<Vec3> positions(info.vertex_count);
  for (size_t i = 0; i < info.vertex_count; ++i)
    positions[i] = Vec3(float(attrib.vertices[3 * i]), float(attrib.vertices[3 * i + 1]),
                        float(attrib.vertices[3 * i + 2]));

  std::vector<UVec3> triangles;
  triangles.reserve(info.triangle_count);
  size_t face = 0;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    size_t offset = 0;
    for (unsigned char corners : shape.mesh.num_face_vertices) {
      const auto* idx = &shape.mesh.indices[offset];
      offset += corners;
      // Shapes come in file order; check each face against the validation pass so the
      // numbering is exactly docs/hits.md's whatever tinyobjloader does with groups.
      if (face >= info.face_heads.size() || uint32_t(idx[0].vertex_index) != info.face_heads[face][0] ||
          uint32_t(idx[1].vertex_index) != info.face_heads[face][1])
        return make_error(path + ": internal: face order from tinyobjloader differs from the file");
      ++face;
      for (unsigned k = 2; k < corners; ++k)  // fan: (v0,v1,v2), (v0,v2,v3), ...
        triangles.emplace_back(idx[0].vertex_index, idx[k - 1].vertex_index, idx[k].vertex_index);
    }
  }
  if (face != info.face_heads.size())
    return make_error(path + ": internal: tinyobjloader read " + std::to_string(face) + " faces, validation counted " +
                      std::to_string(info.face_heads.size()));
  std::string name = path;
  if (const size_t slash = name.find_last_of('/'); slash != std::string::npos) name = name.substr(slash + 1);
  return Scene(std::move(positions), std::move(triangles), name);
}

}  // namespace accel
