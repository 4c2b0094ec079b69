// Giving freed memory back to the system between phases.
#pragma once

namespace walkrad {

// Memory freed by every thread stays in the allocator's per-thread arenas (glibc) as free chunks, and
// a later phase's large arrays are mapped afresh beside them: the resident set counts both. Called
// where a phase has freed much (a refinement pass's lists, a round's new-link list, a mesh's links),
// so that the next phase's peak starts from what is in use. Does nothing off glibc.
void release_free_memory();

}  // namespace walkrad
