// Times tinyobjloader alone on one OBJ file, the way core/obj_loader.cpp calls it (the file
// read into a string first, ParseFromString, no triangulation, no vertex colours, no .mtl):
// the share of accelviz's load_obj that is tinyobjloader's, on the same machine.
// Built and run by scripts/bench_obj_load.sh:
//   tinyobj_parse_time FILE.obj REPEATS  ->  "read_ms parse_ms vertices" of the fastest repeat
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include <tiny_obj_loader.h>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: tinyobj_parse_time FILE.obj REPEATS\n");
    return 2;
  }
  const int repeats = std::max(1, std::atoi(argv[2]));
  using Clock = std::chrono::steady_clock;
  double best_read = 1e300, best_parse = 1e300;
  size_t vertices = 0;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = Clock::now();
    std::ifstream in(argv[1], std::ios::binary);
    if (!in) {
      std::fprintf(stderr, "tinyobj_parse_time: cannot open %s\n", argv[1]);
      return 1;
    }
    std::ostringstream buffer;
    buffer << in.rdbuf();
    const std::string text = buffer.str();
    const auto t1 = Clock::now();
    tinyobj::ObjReaderConfig config;
    config.triangulate = false;
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    if (!reader.ParseFromString(text, "", config)) {
      std::fprintf(stderr, "tinyobj_parse_time: %s\n", reader.Error().c_str());
      return 1;
    }
    const auto t2 = Clock::now();
    vertices = reader.GetAttrib().vertices.size() / 3;
    best_read = std::min(best_read, std::chrono::duration<double, std::milli>(t1 - t0).count());
    best_parse = std::min(best_parse, std::chrono::duration<double, std::milli>(t2 - t1).count());
  }
  std::printf("%.3f %.3f %zu\n", best_read, best_parse, vertices);
  return 0;
}
