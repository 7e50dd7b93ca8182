#include "student/kit_registrations.h"

namespace accel {
namespace {

std::vector<accelviz::Registration>& registrations() {
  static std::vector<accelviz::Registration> r;
  return r;
}

}  // namespace

const std::vector<accelviz::Registration>& student_registrations() { return registrations(); }

}  // namespace accel

namespace accelviz {

bool register_student_structure(const Registration& r) {
  accel::registrations().push_back(r);
  return true;
}

}  // namespace accelviz
