#pragma once
// Private: the library's parallel loops (the per-triangle steps, the renderer's chunks and
// bands), in one place. Threads are started per call; a persistent pool is not there yet.

#include <cstddef>
#include <functional>

namespace geolens {

/// Calls fn(begin, end) on disjoint chunks covering [0, n), one chunk per hardware thread
/// (the calling thread takes the first), or once on the calling thread when n < 2 * min_chunk.
/// fn must not write shared state outside its own range.
void parallel_for(size_t n, const std::function<void(size_t, size_t)>& fn, size_t min_chunk = 4096);

/// Calls work(i) for every i in [0, count), handing the indices out in order to `threads`
/// threads (the calling thread included; 0: one per hardware thread), for work of uneven cost.
/// Returns when all are done; rethrows the first exception.
void parallel_for_each(size_t count, const std::function<void(size_t)>& work, int threads = 0);

/// Runs a and b at the same time (b on a second thread) and returns when both are done.
void parallel_invoke(const std::function<void()>& a, const std::function<void()>& b);

}  // namespace geolens
