// Hostile submission: phones home from build(): a TCP connection to 127.0.0.1 on port
// $ACCELVIZ_HOSTILE_PORT (default 47321) sending "hostile connected\n", and a UDP datagram
// with the same text to the same port (failures ignored). Every ray misses. The grader must
// report it FAILED (wrong answers), and no connection or datagram may arrive at a listener
// the test holds on that port: the worker has no network, and seccomp refuses socket().
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <vector>

#include "accelviz_student.h"

using namespace accelviz;

namespace {

void phone_home() {
  const char* env = std::getenv("ACCELVIZ_HOSTILE_PORT");
  const int port = env ? std::atoi(env) : 47321;
  sockaddr_in addr;
  std::memset(&addr, 0, sizeof addr);
  addr.sin_family = AF_INET;
  addr.sin_port = htons(uint16_t(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  const auto* to = reinterpret_cast<const sockaddr*>(&addr);
  static const char kMessage[] = "hostile connected\n";
  if (const int tcp = ::socket(AF_INET, SOCK_STREAM, 0); tcp >= 0) {
    if (::connect(tcp, to, sizeof addr) == 0) {
      [[maybe_unused]] const ssize_t sent = ::send(tcp, kMessage, sizeof kMessage - 1, MSG_NOSIGNAL);
    }
    ::close(tcp);
  }
  if (const int udp = ::socket(AF_INET, SOCK_DGRAM, 0); udp >= 0) {
    [[maybe_unused]] const ssize_t sent = ::sendto(udp, kMessage, sizeof kMessage - 1, 0, to, sizeof addr);
    ::close(udp);
  }
}

class Socket : public StudentStructure {
 public:
  void build(const Scene& scene, BuildLog& log) override {
    std::vector<uint32_t> all;
    for (uint32_t p = 0; p < scene.size(); ++p) all.push_back(p);
    log.node(0, kNoParent, 0, scene.bounds(), all);
    log.leaf(0, all);
    phone_home();
  }
  Hit intersect(const Ray&, TraversalLog) const override { return Hit{}; }
};

}  // namespace

ACCELVIZ_STUDENT_STRUCTURE(Socket, "hostile_socket", bvh)
