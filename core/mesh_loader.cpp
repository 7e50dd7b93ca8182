// PLY, STL and glTF 2.0 / GLB loading through Assimp (Debian's libassimp-dev). Assimp
// parses; this file decides the numbering (docs/hits.md): meshes in the order the scene's
// node tree reaches them (depth first, children in file order; a file whose nodes hold no
// mesh: the meshes in file order), each mesh's faces in file order, a polygon
// fan-triangulated in place as for OBJ. No Assimp post-processing step runs that would
// reorder, merge or re-triangulate (Triangulate ear-clips, JoinIdenticalVertices reorders);
// only ValidateDataStructure, which rejects out-of-range indices.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <assimp/BaseImporter.h>
#include <assimp/Importer.hpp>
#include <assimp/importerdesc.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "scene.h"

namespace accel {
namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string extension_of(const std::string& path) { return lower(std::filesystem::path(path).extension().string()); }

/// Assimp's message on one line (printable: it may quote the input).
std::string one_line(std::string msg) {
  while (!msg.empty() && (msg.back() == '\n' || msg.back() == '\r' || msg.back() == ' ')) msg.pop_back();
  for (char& c : msg)
    if (c == '\n' || c == '\r') c = ' ';
  return printable(msg, 300);
}

/// The PLY header, checked before Assimp sees the file: the format line, elements with
/// their counts, typed properties, `end_header`. Assimp 5.2's PLY reader loops forever on
/// some malformed headers (a property of an unknown type, found by tests/fuzz's fuzz_mesh),
/// so nothing it does not define gets through. A header that claims more elements than the
/// file can hold is rejected here too, before Assimp reserves memory for them (a 100-byte
/// file claiming 10^12 vertices must not be an out-of-memory kill): each vertex needs at
/// least 3 bytes (ASCII "0 0 0" minus spacing is already more; binary floats are 12), each
/// face at least 4.
/// True when the file begins with a PLY signature ("ply" and a line end).
bool starts_like_ply(const std::string& path) {
  char head[4] = {};
  std::ifstream in(path, std::ios::binary);
  in.read(head, sizeof head);
  return in.gcount() == 4 && head[0] == 'p' && head[1] == 'l' && head[2] == 'y' && (head[3] == '\n' || head[3] == '\r');
}

/// What a PLY header declares: the format and, per element, its count and properties.
struct PlyLayout {
  enum class Format { Ascii, BinaryLittle, BinaryBig } format = Format::Ascii;
  struct Property {
    bool list = false;
    int count_size = 0, value_size = 0;  // bytes in binary files; count_size only for lists
  };
  struct Element {
    std::string name;
    uintmax_t count = 0;
    std::vector<Property> properties;
  };
  std::vector<Element> elements;
  uintmax_t body_offset = 0;  // the first byte after end_header's line
  int header_lines = 0;        // end_header's line number: the body's lines follow it
};

/// Bytes of a PLY scalar type (the header check has accepted the name).
int ply_type_size(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "double" || t == "float64") return 8;
  return 4;
}

Status check_ply_header(const std::string& path, uintmax_t file_size, PlyLayout& layout) {
  static const char* const kTypes[] = {"char", "uchar", "short", "ushort", "int", "uint", "float", "double",
                                       "int8", "uint8", "int16", "uint16", "int32", "uint32", "float32", "float64"};
  const auto is_type = [](const std::string& t, bool integral_only) {
    for (const char* k : kTypes)
      if (t == k) return !integral_only || (t.find("float") == std::string::npos && t != "double");
    return false;
  };
  const auto fail = [&](int line, const std::string& what) {
    return make_error(path + ":" + std::to_string(line) + ": PLY header: " + what);
  };
  std::ifstream in(path, std::ios::binary);
  std::string line;
  uintmax_t vertices = 0, faces = 0;
  bool in_element = false;
  for (int n = 1; n <= 1000 && std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (n == 1) {
      if (line != "ply") return fail(n, "the first line must be 'ply'");
      continue;
    }
    if (n == 2) {
      if (line != "format ascii 1.0" && line != "format binary_little_endian 1.0" &&
          line != "format binary_big_endian 1.0")
        return fail(n, "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      layout.format = line == "format ascii 1.0"                    ? PlyLayout::Format::Ascii
                      : line == "format binary_little_endian 1.0" ? PlyLayout::Format::BinaryLittle
                                                                   : PlyLayout::Format::BinaryBig;
      continue;
    }
    if (keyword == "comment" || keyword == "obj_info") continue;
    // Words split by blanks only, as Assimp splits them: a control or non-ASCII byte in an
    // element line let Assimp read a count of 10^40 digits where this check read 8.
    for (char ch : line)
      if ((static_cast<unsigned char>(ch) < 0x20 && ch != '\t') || static_cast<unsigned char>(ch) >= 0x7f)
        return fail(n, "a control or non-ASCII character outside a comment");
    if (keyword == "end_header") {
      const uintmax_t budget = file_size + 1;
      if (vertices > budget / 3 || faces > budget / 4)
        return make_error(path + ": the PLY header declares " + std::to_string(vertices) + " vertices and " +
                          std::to_string(faces) + " faces, more than a file of " + std::to_string(file_size) +
                          " bytes can hold");
      const std::streamoff end = in.tellg();  // -1 when end_header is the file's last bytes
      layout.body_offset = end < 0 ? file_size : static_cast<uintmax_t>(end);
      layout.header_lines = n;
      return {};
    }
    std::string a, b, c, extra;
    if (keyword == "element") {
      if (!(words >> a >> b) || (words >> extra) || b.find_first_not_of("0123456789") != std::string::npos ||
          b.size() > 19)
        return fail(n, "expected 'element NAME COUNT'");
      const uintmax_t count = std::stoull(b);
      if (a == "vertex") vertices = count;
      else if (a == "face") faces = count;
      in_element = true;
      layout.elements.push_back({a, count, {}});
      continue;
    }
    if (keyword == "property") {
      if (!in_element) return fail(n, "a property before the first element");
      if (!(words >> a)) return fail(n, "expected 'property TYPE NAME'");
      if (a == "list") {
        if (!(words >> a >> b >> c) || (words >> extra) || !is_type(a, true) || !is_type(b, true))
          return fail(n, "expected 'property list COUNT_TYPE INDEX_TYPE NAME' with integer types");
        layout.elements.back().properties.push_back({true, ply_type_size(a), ply_type_size(b)});
      } else if (!(words >> b) || (words >> extra) || !is_type(a, false)) {
        return fail(n, "expected 'property TYPE NAME' with TYPE one of char, uchar, short, ushort, int, uint, "
                       "float, double (or int8 ... float64)");
      } else {
        layout.elements.back().properties.push_back({false, 0, ply_type_size(a)});
      }
      continue;
    }
    std::string shown = line.substr(0, 40);
    for (char& ch : shown)
      if (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f) ch = '?';  // one printable line
    return fail(n, "unexpected line '" + shown + "'");
  }
  return make_error(path + ": PLY header: no 'end_header' line within the first 1000 lines");
}

/// An error in a PLY body's list, in instance `index` of element `e`: at `path`, and in an
/// ASCII body at file line `line` (0 in a binary body, which has no lines).
Error ply_list_error(const std::string& path, int line, const PlyLayout::Element& e, uintmax_t index,
                     const std::string& what) {
  const std::string where = line > 0 ? path + ":" + std::to_string(line) : path;
  return make_error(where + ": PLY " + e.name + " " + std::to_string(index) + ": " + what);
}

/// "a list of COUNT entries", COUNT too large to read said so.
std::string list_entries_text(uintmax_t count) {
  return "a list of " + (count == UINTMAX_MAX ? std::string("more than 10^19") : std::to_string(count)) + " entries";
}

/// The ASCII line `text` of instance `index` of element `e`, whose tokens are read up to its
/// last list (property `lists_end` - 1); `after` bytes of the body follow the line, and it
/// is the file's line `line`.
Status check_ascii_ply_line(const std::string& path, int line, const PlyLayout::Element& e, uintmax_t index,
                            size_t lists_end, std::string_view text, size_t after) {
  size_t at = 0;
  const auto token = [&](std::string_view& out) {
    while (at < text.size() && std::isspace(static_cast<unsigned char>(text[at]))) ++at;
    const size_t begin = at;
    while (at < text.size() && !std::isspace(static_cast<unsigned char>(text[at]))) ++at;
    out = text.substr(begin, at - begin);
    return !out.empty();
  };
  for (size_t k = 0; k < lists_end; ++k) {
    const PlyLayout::Property& p = e.properties[k];
    std::string_view t;
    if (!token(t)) break;
    if (!p.list) continue;
    if (t[0] == '-' && t.size() > 1 && std::isdigit(static_cast<unsigned char>(t[1])))
      return ply_list_error(path, line, e, index, "a list of negative length");
    const size_t digits = std::min(t.find_first_not_of("0123456789"), t.size());
    const uintmax_t count = digits > 19 ? UINTMAX_MAX : digits == 0 ? 0 : std::stoull(std::string(t.substr(0, digits)));
    const uintmax_t max_count = p.count_size >= 4 ? uintmax_t(0xFFFFFFFFu) : (uintmax_t(1) << (8 * p.count_size)) - 1;
    if (count > max_count)
      return ply_list_error(path, line, e, index,
                            list_entries_text(count) + ", more than its " + std::to_string(p.count_size) +
                                "-byte count type can say");
    // Each entry takes a character and a blank at least.
    const size_t rest = (text.size() - at) + after;
    if (count > rest / 2 + 1)
      return ply_list_error(path, line, e, index, list_entries_text(count) + ", more than the rest of the file holds");
    if (k + 1 < lists_end)  // another list follows on this line: step over the entries
      for (uintmax_t n = 0; n < count && token(t); ++n) {
      }
  }
  return {};
}

/// Assimp 5.2's line ends (ParsingUtils.h, IsLineEnd): a NUL or a form feed ends a line too.
bool is_assimp_line_end(char c) { return c == '\n' || c == '\r' || c == '\0' || c == '\f'; }

/// The next line of `body` from `pos` as Assimp 5.2's IOStreamBuffer::getNextLine cuts it,
/// and `pos` moved past it: the line runs to the next line end, which is stepped over;
/// a line that would begin at another line end ("\r\n", an empty line, two NULs) first
/// skips everything through the next '\n'. Assimp reads one element instance per line,
/// so the check must cut the same lines: fuzz_mesh found a face line "8\t", a NUL, then
/// "888...883 0 3 2", which Assimp read as two faces, the second with 954,437,172 entries
/// (14.9 GB before its validation refused it), where a cut at '\n' alone saw one harmless face.
std::string_view next_assimp_line(const std::string& body, size_t& pos) {
  if (pos < body.size() && is_assimp_line_end(body[pos])) {
    const size_t newline = body.find('\n', pos);
    pos = newline == std::string::npos ? body.size() : newline + 1;
  }
  size_t end = pos;
  while (end < body.size() && !is_assimp_line_end(body[end])) ++end;
  const std::string_view line(body.data() + pos, end - pos);
  pos = end + 1;
  return line;
}

/// An ASCII body, line by line as Assimp reads it (next_assimp_line): one element instance
/// per line, the list's count read as the digits its token starts with.
Status check_ascii_ply_lists(const std::string& path, const PlyLayout& layout, const std::string& body) {
  size_t pos = 0;
  // The file's line number of `pos`, for the messages: the header's lines, then the body's '\n's.
  int line = layout.header_lines + 1;
  size_t counted = 0;  // body[0, counted) holds the '\n's counted in `line`
  for (const PlyLayout::Element& e : layout.elements) {
    // Tokens up to the last list; an element without one is only skipped, line by line.
    size_t lists_end = 0;
    for (size_t k = 0; k < e.properties.size(); ++k)
      if (e.properties[k].list) lists_end = k + 1;
    for (uintmax_t i = 0; i < e.count; ++i) {
      if (pos >= body.size()) return {};
      const std::string_view text = next_assimp_line(body, pos);
      if (lists_end == 0) continue;
      const size_t begin = size_t(text.data() - body.data());
      line += int(std::count(body.begin() + long(counted), body.begin() + long(begin), '\n'));
      counted = begin;
      const size_t after = pos < body.size() ? body.size() - pos : 0;
      if (Status st = check_ascii_ply_line(path, line, e, i, lists_end, text, after); !st) return st;
    }
  }
  return {};
}

/// A binary body, walked as the header lays it out: each list's count in its count type's
/// bytes, then its entries.
Status check_binary_ply_lists(const std::string& path, const PlyLayout& layout, const std::string& body) {
  const bool big = layout.format == PlyLayout::Format::BinaryBig;
  size_t pos = 0;
  for (const PlyLayout::Element& e : layout.elements) {
    size_t row = 0;  // bytes of one instance when it holds no list
    bool has_list = false;
    for (const PlyLayout::Property& p : e.properties) {
      has_list |= p.list;
      row += size_t(p.value_size);
    }
    if (!has_list) {
      if (row != 0 && e.count > (body.size() - pos) / row) return {};  // ends early: Assimp's to report
      pos += size_t(e.count) * row;
      continue;
    }
    for (uintmax_t i = 0; i < e.count; ++i) {
      for (const PlyLayout::Property& p : e.properties) {
        if (!p.list) {
          if (body.size() - pos < size_t(p.value_size)) return {};
          pos += size_t(p.value_size);
          continue;
        }
        if (body.size() - pos < size_t(p.count_size)) return {};
        uintmax_t count = 0;
        for (int k = 0; k < p.count_size; ++k) {
          const auto byte = static_cast<unsigned char>(body[pos + size_t(big ? k : p.count_size - 1 - k)]);
          count = count << 8 | byte;
        }
        pos += size_t(p.count_size);
        if (count > (body.size() - pos) / size_t(p.value_size))
          return ply_list_error(path, 0, e, i, list_entries_text(count) + ", more than the rest of the file holds");
        pos += size_t(count) * size_t(p.value_size);
      }
    }
  }
  return {};
}

/// The PLY body's list lengths, checked before Assimp sees them: Assimp 5.2 reserves what a
/// face's count says, so an ASCII face "88888888883 0 3 2" in a 430-byte file asked for
/// 7.6 GB (fuzz_mesh found it). The body is walked as the header lays it out; a list longer
/// than its count type can say or than the rest of the file can hold is a one-line error.
/// Where the body ends early or holds something that is no number, the walk stops and
/// Assimp gives its own error.
Status check_ply_lists(const std::string& path, const PlyLayout& layout) {
  std::ifstream in(path, std::ios::binary);
  in.seekg(static_cast<std::streamoff>(layout.body_offset));
  std::string body((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (layout.format == PlyLayout::Format::Ascii) return check_ascii_ply_lists(path, layout, body);
  return check_binary_ply_lists(path, layout, body);
}

/// True when the file begins with the binary glTF magic "glTF".
bool starts_like_glb(const std::string& path) {
  char head[4] = {};
  std::ifstream in(path, std::ios::binary);
  in.read(head, sizeof head);
  return in.gcount() == 4 && std::string(head, 4) == "glTF";
}

/// The binary glTF container, checked before Assimp sees the file. Assimp 5.2 allocates
/// what the header and chunk lengths claim before it reads them, so a 600-byte file whose
/// JSON chunk claims 1.8 GB asked for 1.8 GB (fuzz_mesh found it): every length must fit in
/// the file. Version 1 (KHR_binary_glTF) has one content length, version 2 a chunk list.
Status check_glb_container(const std::string& path, uintmax_t file_size) {
  std::ifstream in(path, std::ios::binary);
  const auto word = [&](uint32_t& out) {
    unsigned char b[4] = {};
    in.read(reinterpret_cast<char*>(b), 4);
    out = uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24;  // little endian
    return in.gcount() == 4;
  };
  const auto fail = [&](const std::string& what) { return make_error(path + ": GLB header: " + what); };
  uint32_t magic = 0, version = 0, length = 0;
  if (!word(magic) || !word(version) || !word(length)) return fail("shorter than its 12-byte header");
  const std::string file_bytes = "the file has " + std::to_string(file_size) + " bytes";
  if (length > file_size) return fail("declares " + std::to_string(length) + " bytes but " + file_bytes);
  if (version == 1) {
    uint32_t content_length = 0, content_format = 0;
    if (!word(content_length) || !word(content_format)) return fail("shorter than its 20-byte version 1 header");
    if (length < 20 || content_length > length - 20)
      return fail("the content declares " + std::to_string(content_length) + " bytes but " + file_bytes);
    return {};
  }
  if (version != 2) return fail("version " + std::to_string(version) + " (1 or 2 expected)");
  if (length < 20) return fail("declares " + std::to_string(length) + " bytes, less than a header and one chunk");
  // Every chunk up to the end of the file, whatever the header's length says: Assimp reads
  // the JSON chunk by its own length (a header of length 0 hid a 2 GB chunk, fuzz_mesh).
  uint64_t offset = 12;
  for (int chunk = 0; offset + 8 <= file_size; ++chunk) {
    uint32_t chunk_length = 0, chunk_type = 0;
    if (!word(chunk_length) || !word(chunk_type)) break;
    if (chunk_length > file_size - offset - 8)
      return fail("chunk " + std::to_string(chunk) + " declares " + std::to_string(chunk_length) + " bytes but " +
                  file_bytes);
    offset += 8 + uint64_t(chunk_length);
    in.seekg(static_cast<std::streamoff>(offset));
  }
  return {};
}

/// Leaves registered only the Assimp readers that list `ext` (".glb": both glTF readers).
/// Assimp hands a file its own reader rejects to whichever reader claims the bytes, and
/// those are fuzzed by nobody here: fuzz_mesh found a hang in the PLY reader behind a
/// `.glb` name and a heap overflow in another behind "glTB". The removed readers are
/// deleted here, since UnregisterLoader only forgets them.
void keep_only_readers_of(Assimp::Importer& importer, const std::string& ext) {
  const std::string wanted = ext.substr(1);
  std::vector<Assimp::BaseImporter*> others;
  for (size_t i = 0; i < importer.GetImporterCount(); ++i) {
    const aiImporterDesc* desc = importer.GetImporterInfo(i);
    bool lists = false;
    if (desc && desc->mFileExtensions) {
      std::istringstream names(desc->mFileExtensions);
      for (std::string name; names >> name;) lists |= lower(name) == wanted;
    }
    if (!lists) others.push_back(importer.GetImporter(i));
  }
  for (Assimp::BaseImporter* reader : others) {
    importer.UnregisterLoader(reader);
    delete reader;
  }
}

struct Collector {
  const aiScene* scene = nullptr;
  std::vector<Vec3> positions;
  std::vector<UVec3> triangles;
  std::vector<uint8_t> mesh_used;
  std::string error;

  /// Appends mesh `m` with the node's transform `to_world`.
  bool add_mesh(unsigned m, const aiMatrix4x4& to_world, bool identity) {
    const aiMesh* mesh = scene->mMeshes[m];
    if (positions.size() + mesh->mNumVertices > 0xFFFFFFFFull) {
      error = "more than 2^32 vertices";
      return false;
    }
    const uint32_t base = static_cast<uint32_t>(positions.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      aiVector3D p = mesh->mVertices[v];
      if (!identity) p = to_world * p;
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
        error = "mesh " + std::to_string(m) + " vertex " + std::to_string(v) + " has a non-finite coordinate";
        return false;
      }
      positions.emplace_back(p.x, p.y, p.z);
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices < 3) continue;  // points and lines: no triangles (as OBJ's p and l)
      for (unsigned k = 0; k < face.mNumIndices; ++k) {
        if (face.mIndices[k] >= mesh->mNumVertices) {
          error = "mesh " + std::to_string(m) + " face " + std::to_string(f) + " has an index out of range";
          return false;
        }
      }
      for (unsigned k = 2; k < face.mNumIndices; ++k)  // fan: (v0,v1,v2), (v0,v2,v3), ...
        triangles.emplace_back(base + face.mIndices[0], base + face.mIndices[k - 1], base + face.mIndices[k]);
    }
    return true;
  }

  bool walk(const aiNode* node, const aiMatrix4x4& parent, int depth) {
    if (depth > 256) {
      error = "the node tree is deeper than 256 levels";
      return false;
    }
    const aiMatrix4x4 to_world = parent * node->mTransformation;
    const bool identity = to_world.IsIdentity();
    for (unsigned i = 0; i < node->mNumMeshes; ++i) {
      const unsigned m = node->mMeshes[i];
      if (m >= scene->mNumMeshes) {
        error = "a node refers to mesh " + std::to_string(m) + " of " + std::to_string(scene->mNumMeshes);
        return false;
      }
      mesh_used[m] = 1;
      if (!add_mesh(m, to_world, identity)) return false;
    }
    for (unsigned c = 0; c < node->mNumChildren; ++c)
      if (!walk(node->mChildren[c], to_world, depth + 1)) return false;
    return true;
  }
};

}  // namespace

Result<Scene> load_mesh(const std::string& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) return make_error(path + ": cannot open the file");
  if (std::filesystem::is_directory(status)) return make_error(path + ": is a directory, not a mesh file");
  const uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) return make_error(path + ": cannot read the file size");
  if (size == 0) return make_error(path + ": the file is empty");
  // The checks go by the content as well as by the name: a PLY named .glb once reached the
  // PLY reader (fuzz_mesh found one that hung). keep_only_readers_of() below now stops that,
  // and a PLY's own error line says more than the glTF reader's refusal.
  if (extension_of(path) == ".ply" || starts_like_ply(path)) {
    PlyLayout layout;
    if (Status st = check_ply_header(path, size, layout); !st) return st.error();
    if (Status st = check_ply_lists(path, layout); !st) return st.error();
  }
  if (starts_like_glb(path))
    if (Status st = check_glb_container(path, size); !st) return st.error();

  Assimp::Importer importer;
  keep_only_readers_of(importer, extension_of(path));
  const aiScene* scene = nullptr;
  try {
    scene = importer.ReadFile(path, aiProcess_ValidateDataStructure);
  } catch (const std::exception& e) {  // Assimp reports through GetErrorString; a throw is a failed allocation
    return make_error(path + ": " + one_line(e.what()));
  }
  if (!scene) return make_error(path + ": " + one_line(importer.GetErrorString()));
  if ((scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || scene->mNumMeshes == 0 || !scene->mRootNode)
    return make_error(path + ": no triangles (the file holds no mesh)");

  Collector c;
  c.scene = scene;
  c.mesh_used.assign(scene->mNumMeshes, 0);
  if (!c.walk(scene->mRootNode, aiMatrix4x4(), 0)) return make_error(path + ": " + c.error);
  if (c.triangles.empty() && c.positions.empty()) {
    // No node holds a mesh: take them in file order, untransformed.
    for (unsigned m = 0; m < scene->mNumMeshes; ++m)
      if (!c.add_mesh(m, aiMatrix4x4(), true)) return make_error(path + ": " + c.error);
  }
  if (c.triangles.empty()) return make_error(path + ": no triangles (only points or lines)");
  std::string name = std::filesystem::path(path).filename().string();
  return Scene(std::move(c.positions), std::move(c.triangles), name);
}

}  // namespace accel
