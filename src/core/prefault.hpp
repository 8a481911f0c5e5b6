// Page faults taken ahead, on the thread that has time for them.
#pragma once
#include <cstddef>

namespace deltamesh::detail {

// Maps the whole pages inside [p, p + bytes) writable now, with
// madvise(MADV_POPULATE_WRITE) (Linux 5.14 and later; elsewhere, or when
// the call fails, nothing happens). The memory's contents do not change:
// only the page faults of a later write, on some other thread, happen here
// instead. The range must lie inside one allocation of this process.
void prefault_for_write(void* p, std::size_t bytes);

}  // namespace deltamesh::detail
