#include "walkrad/core/free_memory.h"

#include <cstdlib>  // defines __GLIBC__ where it applies
#if defined(__GLIBC__)
#include <malloc.h>  // malloc_trim
#endif

namespace walkrad {

void release_free_memory() {
#if defined(__GLIBC__)
  malloc_trim(0);  // every arena, whole free pages inside the heaps too (glibc 2.8 and later)
#endif
}

}  // namespace walkrad
