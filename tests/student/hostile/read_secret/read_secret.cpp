// Hostile submission: tries to read a secret (the hidden test data, the grader's key, the
// machine's password hashes) and leak it through an error message: reads the first readable
// file of $ACCELVIZ_HOSTILE_SECRET, /tmp/accelviz-hostile-secret.txt, ../secret.txt (up to
// three levels up), $HOME/secret.txt, /etc/shadow, /etc/hostname and throws
// "leaked: <contents>" from build(). The grader must report it FAILED (the build threw), and
// the secret must appear nowhere in its output or report: the sandbox shows the worker no
// /tmp, $HOME, /etc or working directory of the judge's, so the best it can say is
// "leaked: nothing readable".
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "accelviz_student.h"

using namespace accelviz;

namespace {

class ReadSecret : public StudentStructure {
 public:
  void build(const Scene& scene, BuildLog& log) override {
    std::vector<uint32_t> all;
    for (uint32_t p = 0; p < scene.size(); ++p) all.push_back(p);
    log.node(0, kNoParent, 0, scene.bounds(), all);
    log.leaf(0, all);
    std::vector<std::string> paths;
    if (const char* secret = std::getenv("ACCELVIZ_HOSTILE_SECRET")) paths.push_back(secret);
    paths.insert(paths.end(), {"/tmp/accelviz-hostile-secret.txt", "../secret.txt", "../../secret.txt",
                               "../../../secret.txt"});
    if (const char* home = std::getenv("HOME")) paths.push_back(std::string(home) + "/secret.txt");
    paths.insert(paths.end(), {"/etc/shadow", "/etc/hostname"});
    for (const std::string& path : paths) {
      std::ifstream in(path, std::ios::binary);
      if (!in) continue;
      const std::string contents{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
      if (!in.bad()) throw std::runtime_error("leaked: " + contents);
    }
    throw std::runtime_error("leaked: nothing readable");
  }
  Hit intersect(const Ray&, TraversalLog) const override { return Hit{}; }
};

}  // namespace

ACCELVIZ_STUDENT_STRUCTURE(ReadSecret, "hostile_read_secret", bvh)
