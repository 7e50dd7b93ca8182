// Hostile submission: writes "hostile_write_outside was here" to files outside its own
// folder in build(): /tmp/accelviz-hostile-wrote.txt, $HOME/accelviz-hostile-wrote.txt,
// ../accelviz-hostile-wrote.txt and /var/tmp/accelviz-hostile-wrote.txt (errors ignored).
// Every ray misses. The grader must report it FAILED (wrong answers), and none of these
// files may appear on the machine: the worker's /tmp and $HOME are private and empty, and
// everything else it sees is read-only or absent.
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "accelviz_student.h"

using namespace accelviz;

namespace {

class WriteOutside : public StudentStructure {
 public:
  void build(const Scene& scene, BuildLog& log) override {
    std::vector<uint32_t> all;
    for (uint32_t p = 0; p < scene.size(); ++p) all.push_back(p);
    log.node(0, kNoParent, 0, scene.bounds(), all);
    log.leaf(0, all);
    std::vector<std::string> paths = {"/tmp/accelviz-hostile-wrote.txt", "../accelviz-hostile-wrote.txt",
                                      "/var/tmp/accelviz-hostile-wrote.txt"};
    if (const char* home = std::getenv("HOME")) paths.push_back(std::string(home) + "/accelviz-hostile-wrote.txt");
    for (const std::string& path : paths) {
      std::ofstream out(path, std::ios::trunc);
      out << "hostile_write_outside was here\n";  // a stream that failed to open writes nothing
    }
  }
  Hit intersect(const Ray&, TraversalLog) const override { return Hit{}; }
};

}  // namespace

ACCELVIZ_STUDENT_STRUCTURE(WriteOutside, "hostile_write_outside", bvh)
