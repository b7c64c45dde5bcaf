#pragma once
// Private: a minimal parallel loop over index ranges for the per-triangle steps.

#include <cstddef>
#include <functional>

namespace geolens {

/// Calls fn(begin, end) on disjoint chunks covering [0, n), one chunk per hardware thread
/// (the calling thread takes the first), or once on the calling thread when n < 2 * min_chunk.
/// fn must not write shared state outside its own range.
void parallel_for(size_t n, const std::function<void(size_t, size_t)>& fn, size_t min_chunk = 4096);

/// Runs a and b at the same time (b on a second thread) and returns when both are done.
void parallel_invoke(const std::function<void()>& a, const std::function<void()>& b);

}  // namespace geolens
