#pragma once
// CHECK / DCHECK: internal invariants. A failed CHECK is a bug in accelviz, never bad
// input (bad input returns an Error, see result.h), so it aborts with the location.
#include <cstdio>
#include <cstdlib>

#define ACCEL_CHECK(cond)                                                              \
  do {                                                                                 \
    if (!(cond)) {                                                                     \
      std::fprintf(stderr, "%s:%d: internal check failed: %s\n", __FILE__, __LINE__, #cond); \
      std::abort();                                                                    \
    }                                                                                  \
  } while (0)

#ifdef NDEBUG
#define ACCEL_DCHECK(cond) ((void)0)
#else
#define ACCEL_DCHECK(cond) ACCEL_CHECK(cond)
#endif
