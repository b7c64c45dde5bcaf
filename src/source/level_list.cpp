#include "source/level_list.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/io/file_io.h"
#include "source/convert_channels.h"
#include "source/downsample.h"

namespace geolens {

namespace {

constexpr const char* kFn = "open_level_list";
constexpr size_t kMaxListBytes = size_t(16) << 20;  ///< a line per level

/// One image of the list.
struct ListedImage {
  std::string path;  ///< as opened (resolved against the list's folder)
  std::string name;  ///< as written in the list
  int line = 0;      ///< 1-based line of the list
  int width = 0, height = 0;
};

/// Big-endian unsigned integer of `n` bytes at `p`.
uint32_t big_endian(const unsigned char* p, int n) {
  uint32_t v = 0;
  for (int i = 0; i < n; ++i) v = (v << 8) | p[i];
  return v;
}

/// The size of a PNG (from its IHDR chunk) or JPEG (from its first SOF segment) file, read from
/// its header without decoding; an empty string in `why` when it succeeds, else what is wrong.
std::pair<int, int> image_size(const std::string& path, std::string& why) {
  std::ifstream in(path, std::ios::binary);
  if (!in || std::filesystem::is_directory(path)) {
    why = "cannot be opened";
    return {0, 0};
  }
  unsigned char head[24] = {};
  in.read(reinterpret_cast<char*>(head), sizeof head);
  const std::streamsize got = in.gcount();
  static const unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (got >= 24 && std::equal(kPng, kPng + 8, head)) {
    if (big_endian(head + 12, 4) != big_endian(reinterpret_cast<const unsigned char*>("IHDR"), 4)) {
      why = "is a PNG without an IHDR chunk first";
      return {0, 0};
    }
    const uint32_t w = big_endian(head + 16, 4), h = big_endian(head + 20, 4);
    if (w == 0 || h == 0 || w > (1u << 30) || h > (1u << 30)) {
      why = "is a PNG of invalid size " + std::to_string(w) + " x " + std::to_string(h);
      return {0, 0};
    }
    return {int(w), int(h)};
  }
  if (got < 2 || head[0] != 0xFF || head[1] != 0xD8) {
    why = "is not a PNG or JPEG file";
    return {0, 0};
  }
  // JPEG: walk the marker segments after SOI up to the first start-of-frame.
  in.clear();
  in.seekg(2);
  for (;;) {
    int byte = in.get();
    while (in && byte != 0xFF) byte = in.get();  // to the next marker
    while (in && byte == 0xFF) byte = in.get();  // over fill bytes
    if (!in || byte == 0xD9 || byte == 0xDA) break;
    const int marker = byte;
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) continue;  // no length
    unsigned char segment[7];
    in.read(reinterpret_cast<char*>(segment), 2);
    if (!in) break;
    const uint32_t length = big_endian(segment, 2);
    const bool start_of_frame =
        marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (start_of_frame) {
      in.read(reinterpret_cast<char*>(segment + 2), 5);
      if (!in) break;
      const uint32_t h = big_endian(segment + 3, 2), w = big_endian(segment + 5, 2);
      if (w == 0 || h == 0) {
        why = "is a JPEG of size " + std::to_string(w) + " x " + std::to_string(h);
        return {0, 0};
      }
      return {int(w), int(h)};
    }
    if (length < 2) break;
    in.seekg(std::streamoff(length) - 2, std::ios::cur);
  }
  why = "is a JPEG without a frame header";
  return {0, 0};
}

/// '<name>' (line <n>)
std::string named(const ListedImage& image) {
  return "'" + image.name + "' (line " + std::to_string(image.line) + ")";
}

/// Decodes `listed`, converted to `channels` (0: as stored); `list` is the list file's path.
Image decode_listed(const ListedImage& listed, const std::string& list, int channels) {
  Image image;
  try {
    image = load_image(listed.path);
  } catch (const InvalidInput& e) {
    throw InvalidInput(std::string(kFn) + ": '" + list + "' line " + std::to_string(listed.line) +
                       ": " + e.what());
  }
  require(image.width == listed.width && image.height == listed.height, kFn,
          "'" + list + "' line " + std::to_string(listed.line) + ": '" + listed.name +
              "' decodes to " + std::to_string(image.width) + " x " + std::to_string(image.height) +
              ", its header says " + std::to_string(listed.width) + " x " +
              std::to_string(listed.height));
  const int to = channels > 0 ? channels : image.channels;
  return convert_channels(std::move(image), to);
}

/// The level list as a Source: each level a whole image, decoded from its file or downsampled
/// from the next finer level when first fetched, in an LRU cache of whole levels.
class LevelListSource : public Source {
 public:
  LevelListSource(int width, int height, int channels, std::vector<ListedImage> images,
                  std::vector<int> image_of_level, std::string list, size_t budget)
      : Source(width, height, channels, kFn),
        images_(std::move(images)),
        image_of_level_(std::move(image_of_level)),
        list_(std::move(list)),
        budget_(budget) {
    image_of_level_.resize(size_t(levels()), -1);
  }

  /// Level `level`, from the cache or decoded / made (and cached).
  std::shared_ptr<const Image> level(int level) const {
    std::unique_lock<std::mutex> lock(mutex_);
    if (const auto hit = cached_.find(level); hit != cached_.end()) {
      hit->second.last_used = ++clock_;
      return hit->second.image;
    }
    if (const auto pending = being_made_.find(level); pending != being_made_.end()) {
      const std::shared_future<std::shared_ptr<const Image>> made = pending->second;
      lock.unlock();
      return made.get();
    }
    std::promise<std::shared_ptr<const Image>> promise;
    being_made_.emplace(level, promise.get_future().share());
    lock.unlock();
    std::shared_ptr<const Image> made;
    try {
      made = std::make_shared<const Image>(make(level));
    } catch (...) {
      lock.lock();
      being_made_.erase(level);
      lock.unlock();
      promise.set_exception(std::current_exception());
      throw;
    }
    lock.lock();
    being_made_.erase(level);
    insert(level, made);
    lock.unlock();
    promise.set_value(made);
    return made;
  }

  /// Keeps `image`, the image of `level` decoded by the caller, as if fetched.
  void keep(int level, Image image) const {
    ++decoded_;
    image = pad(std::move(image), level);
    std::lock_guard<std::mutex> lock(mutex_);
    insert(level, std::make_shared<const Image>(std::move(image)));
  }

  /// `image` (level `level`'s image, possibly a texel short on a side) padded to the level's
  /// size by repeating its last column and row.
  Image pad(Image image, int level) const {
    const int w = level_width(level), h = level_height(level);
    if (image.width == w && image.height == h) return image;
    Image out(w, h, image.channels);
    const size_t texel = size_t(image.channels);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        std::copy_n(image.at(std::min(x, image.width - 1), std::min(y, image.height - 1)), texel,
                    out.at(x, y));
    return out;
  }

  size_t images_decoded() const { return decoded_; }
  size_t levels_made() const { return made_; }

 private:
  struct Cached {
    std::shared_ptr<const Image> image;
    uint64_t last_used = 0;
  };

  Image make(int level) const {
    const int index = image_of_level_[size_t(level)];
    if (index >= 0) {
      Image image = decode_listed(images_[size_t(index)], list_, channels());
      ++decoded_;
      return pad(std::move(image), level);
    }
    const std::shared_ptr<const Image> finer = this->level(level - 1);
    Image coarse = downsample(*finer);
    ++made_;
    return coarse;
  }

  /// Caches `image` as `level`, first evicting the least recently used levels until it fits
  /// (or nothing else is left). Called under the lock.
  void insert(int level, std::shared_ptr<const Image> image) const {
    const size_t bytes = image->pixels.size();
    while (bytes_ + bytes > budget_ && !cached_.empty()) {
      auto oldest = cached_.begin();
      for (auto it = cached_.begin(); it != cached_.end(); ++it)
        if (it->second.last_used < oldest->second.last_used) oldest = it;
      bytes_ -= oldest->second.image->pixels.size();
      cached_.erase(oldest);
    }
    cached_[level] = Cached{std::move(image), ++clock_};
    bytes_ += bytes;
  }

  TexelRegion fetch_inside(int level, int x, int y, int width, int height) const override {
    std::shared_ptr<const Image> image = this->level(level);
    TexelRegion region;
    region.data = image->at(x, y);
    region.stride = size_t(image->width) * size_t(image->channels);
    region.x = x;
    region.y = y;
    region.width = width;
    region.height = height;
    region.channels = channels();
    region.owner = std::move(image);
    return region;
  }

  std::vector<ListedImage> images_;
  std::vector<int> image_of_level_;  ///< per level, the index of its image, or -1: made
  std::string list_;
  size_t budget_;
  mutable std::mutex mutex_;
  mutable std::map<int, Cached> cached_;
  mutable std::map<int, std::shared_future<std::shared_ptr<const Image>>> being_made_;
  mutable uint64_t clock_ = 0;
  mutable size_t bytes_ = 0;
  mutable std::atomic<size_t> decoded_{0}, made_{0};
};

// The images named by the level list `text` read from `path`: name, line and path (resolved
// against the list's folder), sizes not read.
std::vector<ListedImage> listed_images(const std::string& text, const std::string& path) {
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  std::vector<ListedImage> images;
  std::istringstream lines(text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    const size_t last = line.find_last_not_of(" \t\r");
    ListedImage image;
    image.name = line.substr(first, last - first + 1);
    image.line = number;
    const std::filesystem::path named_path(image.name);
    image.path = (named_path.is_absolute() ? named_path : folder / named_path).string();
    images.push_back(std::move(image));
  }
  return images;
}

/// The level (>= 0) an image of width x height is for, of a finest W x H; -1 if its width fits
/// no level, -2 if its width does but its height does not.
int level_of(int width, int height, int W, int H) {
  bool width_fits = false;
  // Levels down to the first 1 x 1 one, as Source counts them.
  for (int k = 0; k < 31 && (k == 0 || ((W - 1) >> (k - 1)) + ((H - 1) >> (k - 1)) > 0); ++k) {
    const int up_w = ((W - 1) >> k) + 1, down_w = std::max(W >> k, 1);
    const int up_h = ((H - 1) >> k) + 1, down_h = std::max(H >> k, 1);
    if (width != up_w && width != down_w) continue;
    width_fits = true;
    if (height == up_h || height == down_h) return k;
  }
  return width_fits ? -2 : -1;
}

}  // namespace

SourceFile open_level_list(const std::string& path, const SourceFileOptions& options,
                           size_t cache_bytes) {
  require(options.width >= 0 && options.height >= 0, kFn,
          "the frame size must be >= 0, got " + std::to_string(options.width) + " x " +
              std::to_string(options.height));
  std::vector<ListedImage> images;
  for (ListedImage image : listed_images(read_file(path, kFn, "level list", kMaxListBytes), path)) {
    const int number = image.line;
    std::string why;
    std::tie(image.width, image.height) = image_size(image.path, why);
    require(why.empty(), kFn,
            "'" + path + "' line " + std::to_string(number) + ": '" + image.name + "' " + why);
    images.push_back(std::move(image));
  }
  require(!images.empty(), kFn, "'" + path + "' names no image");

  // The finest: the widest (the tallest of the widest).
  const auto finest_it = std::max_element(images.begin(), images.end(), [](auto& a, auto& b) {
    return std::pair(a.width, a.height) < std::pair(b.width, b.height);
  });
  const ListedImage finest = *finest_it;
  const int W = finest.width, H = finest.height;
  std::vector<int> level_image;  // per level
  int coarsest = -1;             // the level of the coarsest image
  for (size_t i = 0; i < images.size(); ++i) {
    const ListedImage& image = images[i];
    const int level = level_of(image.width, image.height, W, H);
    const std::string size = std::to_string(image.width) + " x " + std::to_string(image.height);
    const std::string finest_size = std::to_string(W) + " x " + std::to_string(H);
    require(level != -2, kFn,
            "'" + path + "' line " + std::to_string(image.line) + ": '" + image.name + "' is " +
                size + ", not the finest image " + named(finest) + " of " + finest_size +
                " halved: its width gives a level whose height differs, so the extents (aspect "
                "ratios) disagree");
    require(level != -1, kFn,
            "'" + path + "' line " + std::to_string(image.line) + ": '" + image.name + "' is " +
                size + ": its width is not the finest image " + named(finest) + "'s " +
                std::to_string(W) + " halved a whole number of times (" +
                std::to_string((W + 1) / 2) + ", " + std::to_string((W + 3) / 4) + ", ...)");
    if (size_t(level) >= level_image.size()) level_image.resize(size_t(level) + 1, -1);
    const int other = level_image[size_t(level)];
    require(other < 0, kFn,
            "'" + path + "': " + named(images[size_t(other < 0 ? 0 : other)]) + " and " +
                named(image) + " are both level " + std::to_string(level) + " (" +
                std::to_string(((W - 1) >> level) + 1) + " x " +
                std::to_string(((H - 1) >> level) + 1) + ")");
    level_image[size_t(level)] = int(i);
    coarsest = std::max(coarsest, level);
  }

  // Channels: the coarsest image's, decoded now and kept as its level.
  Image coarse = decode_listed(images[size_t(level_image[size_t(coarsest)])], path, 0);
  const auto source = std::make_shared<const LevelListSource>(
      W, H, coarse.channels, std::move(images), std::move(level_image), path, cache_bytes);
  source->keep(coarsest, std::move(coarse));

  int frame_level = coarsest;
  const int target = options.width > 0 ? options.width : options.height;
  if (target > 0) {
    auto distance = [&](int level) {
      const int side = options.width > 0 ? source->level_width(level) : source->level_height(level);
      return std::abs(std::log(double(side) / target));
    };
    frame_level = 0;
    for (int level = 1; level < source->levels(); ++level)
      if (distance(level) < distance(frame_level) - 1e-12) frame_level = level;
  }
  SourceFile file;
  file.frame_width = source->level_width(frame_level);
  file.frame_height = source->level_height(frame_level);
  file.scale = std::ldexp(1.0, frame_level);
  file.kind = "level list";
  file.counters = [source] {
    return std::vector<std::pair<std::string, double>>{
        {"images_decoded", double(source->images_decoded())},
        {"levels_made", double(source->levels_made())}};
  };
  file.source = source;
  return file;
}

std::vector<std::string> level_list_images(const std::string& path) {
  std::vector<std::string> paths;
  try {
    for (const ListedImage& image : listed_images(read_file(path, kFn, "level list"), path))
      paths.push_back(image.path);
  } catch (const InvalidInput&) {
    // Unreadable: open_level_list names it.
  }
  return paths;
}

}  // namespace geolens
