#pragma once
// The student structures registered in this program by ACCELVIZ_STUDENT_STRUCTURE: in the
// viewer and the web page (which link a student's code directly) and in the worker
// (accelviz-worker, which the judge talks to). Never in the judge: accelviz-cli links no
// student code.
#include <vector>

#include "accelviz_student.h"

namespace accel {

/// Every registration made at program start, in the order the initialisers ran.
const std::vector<accelviz::Registration>& student_registrations();

}  // namespace accel
