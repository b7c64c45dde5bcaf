#include "source/svg_source.h"

#include <librsvg/rsvg.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/io/file_io.h"
#include "geolens/source/source.h"
#include "source/cairo_tile.h"

namespace geolens {

namespace {

constexpr int kMaxFrame = 16384;
constexpr size_t kMaxSvgBytes = size_t(256) << 20;
// librsvg draws the whole document for every tile (clipped to it, not culled): the cost of a tile
// is mostly the document's, not the tile's area, so tiles are large (bench: a zoom-3 view of a
// text page, 2.6 s in 64 tiles of 256, 0.96 s in 22 of 512, 0.52 s in 10 of 1024).
constexpr int kSvgTileSize = 1024;

struct HandleDeleter {
  void operator()(RsvgHandle* handle) const { g_object_unref(handle); }
};
using HandlePtr = std::unique_ptr<RsvgHandle, HandleDeleter>;

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw InvalidInput("open_svg: '" + path + "': " + what);
}

/// The document in `bytes` parsed by librsvg (relative references resolve against `path`), at
/// 96 dots per inch.
HandlePtr parse(const std::string& bytes, const std::string& path) {
  std::unique_ptr<GFile, decltype(&g_object_unref)> base(g_file_new_for_path(path.c_str()),
                                                         &g_object_unref);
  std::unique_ptr<GInputStream, decltype(&g_object_unref)> stream(
      g_memory_input_stream_new_from_data(bytes.data(), gssize(bytes.size()), nullptr),
      &g_object_unref);
  GError* error = nullptr;
  HandlePtr handle(rsvg_handle_new_from_stream_sync(stream.get(), base.get(),
                                                    RSVG_HANDLE_FLAGS_NONE, nullptr, &error));
  if (!handle) {
    std::string message = error ? error->message : "unknown error";
    if (error) g_error_free(error);
    // One line: librsvg's XML errors end with a line break.
    std::replace(message.begin(), message.end(), '\n', ' ');
    while (!message.empty() && message.back() == ' ') message.pop_back();
    fail(path, "librsvg: " + message);
  }
  rsvg_handle_set_dpi(handle.get(), 96.0);
  return handle;
}

/// The handles of one document, each lent to one thread at a time.
class HandlePool {
 public:
  HandlePool(std::string bytes, std::string path, HandlePtr first)
      : bytes_(std::move(bytes)), path_(std::move(path)) {
    free_.push_back(std::move(first));
    count_ = 1;
  }

  /// Calls f(handle) with a handle no other thread uses meanwhile.
  template <class F>
  void with_handle(F&& f) {
    HandlePtr handle;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!free_.empty()) {
        handle = std::move(free_.back());
        free_.pop_back();
      }
    }
    if (!handle) {
      handle = parse(bytes_, path_);  // parsed before: cannot fail but for memory
      std::lock_guard<std::mutex> lock(mutex_);
      ++count_;
    }
    struct Return {
      HandlePool* pool;
      HandlePtr* handle;
      ~Return() {
        std::lock_guard<std::mutex> lock(pool->mutex_);
        pool->free_.push_back(std::move(*handle));
      }
    } give_back{this, &handle};
    f(handle.get());
  }

  int count() {
    std::lock_guard<std::mutex> lock(mutex_);
    return count_;
  }

 private:
  const std::string bytes_, path_;
  std::mutex mutex_;
  std::vector<HandlePtr> free_;
  int count_ = 0;
};

/// The SVG's intrinsic size in CSS pixels: width and height, or else the viewBox; {0, 0} if it
/// has neither.
std::pair<double, double> intrinsic_size(RsvgHandle* handle) {
  double width = 0, height = 0;
  if (rsvg_handle_get_intrinsic_size_in_pixels(handle, &width, &height) && width > 0 && height > 0)
    return {width, height};
  gboolean has_width = false, has_height = false, has_viewbox = false;
  RsvgLength w, h;
  RsvgRectangle viewbox;
  rsvg_handle_get_intrinsic_dimensions(handle, &has_width, &w, &has_height, &h, &has_viewbox,
                                       &viewbox);
  if (has_viewbox && viewbox.width > 0 && viewbox.height > 0)
    return {viewbox.width, viewbox.height};
  return {0, 0};
}

}  // namespace

SourceFile open_svg(const std::string& path, const SourceFileOptions& options) {
  std::string bytes = read_file(path, "open_svg", "SVG", kMaxSvgBytes);
  HandlePtr handle = parse(bytes, path);
  const auto [svg_width, svg_height] = intrinsic_size(handle.get());

  if (options.width < 0 || options.height < 0 || options.width > kMaxFrame ||
      options.height > kMaxFrame)
    fail(path, "the size " + std::to_string(options.width) + " x " +
                   std::to_string(options.height) + " is not in [1, 16384]");
  int width = options.width, height = options.height;
  if (width == 0 || height == 0) {
    if (svg_width <= 0)
      fail(path, "it has no width, height or viewBox: give its size with --size WxH");
    // Sized in doubles and checked before rounding: an SVG 1e30 px wide overflowed an int.
    double w = width, h = height;
    if (width == 0 && height == 0) {
      w = svg_width;
      h = svg_height;
    } else if (width == 0) {
      w = height * svg_width / svg_height;
    } else {
      h = width * svg_height / svg_width;
    }
    if (!(w <= kMaxFrame + 0.5 && h <= kMaxFrame + 0.5))
      fail(path, "its size " + number_text(w) + " x " + number_text(h) +
                     " px is over 16384: give a smaller --size");
    width = std::max(int(std::lround(w)), 1);
    height = std::max(int(std::lround(h)), 1);
  }
  // What the document is drawn into: its intrinsic size, or the frame if it has none.
  const double view_width = svg_width > 0 ? svg_width : width;
  const double view_height = svg_height > 0 ? svg_height : height;
  const double scale = double(1 << kSvgDetail);

  auto pool = std::make_shared<HandlePool>(std::move(bytes), path, std::move(handle));
  TileProvider provider = [pool, path, width, height, view_width, view_height,
                           scale](const TileRequest& request) {
    return cairo_tile(
        request, scale, {255, 255, 255},
        [&](cairo_t* cr) {
          cairo_scale(cr, width / view_width, height / view_height);
          const RsvgRectangle viewport{0, 0, view_width, view_height};
          pool->with_handle([&](RsvgHandle* h) {
            GError* error = nullptr;
            if (!rsvg_handle_render_document(h, cr, &viewport, &error)) {
              const std::string message = error ? error->message : "unknown error";
              if (error) g_error_free(error);
              fail(path, "librsvg could not render it: " + message);
            }
          });
        },
        "open_svg");
  };
  TiledSourceOptions tiles;
  tiles.tile_size = kSvgTileSize;
  auto source = std::make_shared<TiledSource>(int(width * scale), int(height * scale), 3,
                                              std::move(provider), tiles);

  SourceFile file;
  file.frame_width = width;
  file.frame_height = height;
  file.scale = scale;
  file.kind = "svg";
  file.counters = [source, pool]() {
    const TileCacheStats stats = source->cache_stats();
    return std::vector<std::pair<std::string, double>>{
        {"tiles", double(stats.tiles_made)},
        {"cache_peak_mb", double(stats.peak_bytes) / (1 << 20)},
        {"svg_handles", double(pool->count())}};
  };
  file.source = std::move(source);
  return file;
}

}  // namespace geolens
