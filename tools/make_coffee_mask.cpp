// Thresholds the bundled coffee photograph into the mask of its cup rim: the white porcelain
// (low saturation, bright) inside the cup's bounding box, largest 8-connected blob only. Its
// thin left side and wide right side make it a test of a lens on a region of varying width.
//
// Usage: make_coffee_mask examples/coffee.jpg OUTPUT.png

#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cstdio>
#include <vector>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: make_coffee_mask COFFEE.jpg OUTPUT.png\n");
    return 2;
  }
  int w = 0, h = 0, channels = 0;
  unsigned char* rgb = stbi_load(argv[1], &w, &h, &channels, 3);
  if (rgb == nullptr) {
    std::fprintf(stderr, "make_coffee_mask: cannot read '%s': %s\n", argv[1],
                 stbi_failure_reason());
    return 2;
  }
  std::vector<unsigned char> mask(size_t(w) * h, 0);
  for (int y = 10; y < std::min(h, 220); ++y) {
    for (int x = 165; x < std::min(w, 425); ++x) {
      const unsigned char* p = rgb + 3 * (size_t(y) * w + x);
      const int hi = std::max({p[0], p[1], p[2]}), lo = std::min({p[0], p[1], p[2]});
      if (hi > 90 && hi - lo < 0.35 * hi) mask[size_t(y) * w + x] = 255;
    }
  }
  stbi_image_free(rgb);
  // Keep the largest 8-connected blob.
  std::vector<int> label(mask.size(), -1), stack;
  int best = -1;
  size_t best_size = 0;
  for (size_t seed = 0; seed < mask.size(); ++seed) {
    if (!mask[seed] || label[seed] >= 0) continue;
    const int id = int(seed);
    size_t size = 0;
    stack.assign(1, id);
    label[seed] = id;
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      ++size;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int x = i % w + dx, y = i / w + dy;
          if (x < 0 || y < 0 || x >= w || y >= h) continue;
          const int j = y * w + x;
          if (mask[size_t(j)] && label[size_t(j)] < 0) {
            label[size_t(j)] = id;
            stack.push_back(j);
          }
        }
    }
    if (size > best_size) {
      best_size = size;
      best = id;
    }
  }
  for (size_t i = 0; i < mask.size(); ++i) mask[i] = label[i] == best ? 255 : 0;
  if (!stbi_write_png(argv[2], w, h, 1, mask.data(), w)) {
    std::fprintf(stderr, "make_coffee_mask: cannot write '%s'\n", argv[2]);
    return 1;
  }
  return 0;
}
