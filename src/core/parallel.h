#pragma once
// Private: the library's parallel loops over chunks and pairs (the lens's per-triangle steps, its
// x and y factorizations), run on a ThreadPool the caller owns. Loops of uneven items (the
// renderer's chunks and bands) call ThreadPool::run directly.

#include <cstddef>
#include <functional>

#include "core/thread_pool.h"

namespace geolens {

/// Calls fn(begin, end) on disjoint chunks covering [0, n), one chunk per thread of `pool` (at
/// most n / min_chunk chunks), or once on the calling thread when n < 2 * min_chunk or the pool
/// has one thread. fn must not write shared state outside its own range. Returns when all are
/// done; rethrows the first exception (ThreadPool::run).
void parallel_for(ThreadPool& pool, size_t n, const std::function<void(size_t, size_t)>& fn,
                  size_t min_chunk = 4096);

/// Runs a and b on `pool`, at the same time when it has a free worker, and returns when both
/// are done; rethrows the first exception (if a throws before b has started, b is skipped).
void parallel_invoke(ThreadPool& pool, const std::function<void()>& a,
                     const std::function<void()>& b);

}  // namespace geolens
