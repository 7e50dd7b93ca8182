#include "warm_start.h"

#include <cstdlib>  // defines __GLIBC__ where it applies

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace accel {

void prepare_for_builds() {
#if defined(__GLIBC__)
  // Blocks up to 32 MiB (glibc's ceiling for this setting) come from the heap and return to
  // it when freed, and the heap keeps up to 1 GiB of free memory at its top instead of
  // trimming it, so the first build reuses the pages the loader faulted in, and each rebuild
  // (the viewer rebuilds on every parameter change) those of the build before. Larger blocks
  // (scenes of millions of triangles) are still mapped and unmapped one by one: there the
  // faults are a small part of the build.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
}

}  // namespace accel
