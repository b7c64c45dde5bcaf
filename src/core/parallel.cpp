#include "core/parallel.h"

#include <algorithm>

namespace geolens {

void parallel_for(ThreadPool& pool, size_t n, const std::function<void(size_t, size_t)>& fn,
                  size_t min_chunk) {
  const size_t chunks = std::min(size_t(pool.size()), n / std::max<size_t>(min_chunk, 1));
  if (chunks < 2) {
    fn(0, n);
    return;
  }
  const size_t chunk = (n + chunks - 1) / chunks;
  pool.run(chunks, [&](size_t c) {
    const size_t begin = std::min(n, c * chunk), end = std::min(n, begin + chunk);
    if (begin < end) fn(begin, end);
  });
}

void parallel_invoke(ThreadPool& pool, const std::function<void()>& a,
                     const std::function<void()>& b) {
  pool.run(2, [&](size_t i) { i == 0 ? a() : b(); });
}

}  // namespace geolens
