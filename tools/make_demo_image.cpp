// make_demo_image: draws geolens's bundled demo image, a procedural 1024 x 1024 RGB city map
// with the kind of fine detail a focus+context lens is meant for: a street grid crossed by
// diagonal avenues and a curved river, small blocks of buildings, parks, round plazas, node-link
// clusters, and many labels too small to read at 1x that become readable magnified 2-3x.
//
// Usage: make_demo_image OUTPUT.png
// Exit code 0 on success, 1 if the file cannot be written, 2 on bad usage.
//
// The image is deterministic: every random choice comes from a std::mt19937 with a fixed seed
// (its output sequence is fixed by the C++ standard) and nothing depends on time or the
// environment. Shapes are drawn hard-edged on a 4x4 supersampled canvas that is box-filtered
// down, so every edge and every letter is antialiased the same way.

#include <stb_easy_font.h>
#include <stb_image_write.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <string>
#include <system_error>
#include <vector>

namespace {

constexpr int kSize = 1024;              // output width and height, pixels
constexpr int kSuper = 4;                // subsamples per output pixel along each axis
constexpr int kCanvas = kSize * kSuper;  // canvas width and height, subsamples
constexpr double kPi = std::numbers::pi;

struct Rgb {
  std::uint8_t r, g, b;
};

/// A point or direction in output pixels: x right, y down, origin at the image's top-left.
struct Vec2 {
  double x, y;
};

Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
double length(Vec2 a) { return std::hypot(a.x, a.y); }

/// Unit vector at `angle` radians, clockwise on screen from +x (y points down).
Vec2 direction(double angle) { return {std::cos(angle), std::sin(angle)}; }

/// An axis-aligned box, output pixels.
struct Box {
  double x0, y0, x1, y1;
  bool overlaps(const Box& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
};

namespace palette {
constexpr Rgb kLand{242, 239, 233};
constexpr Rgb kYard{231, 225, 217};
constexpr std::array<Rgb, 4> kBuildings{
    {{217, 208, 201}, {223, 212, 196}, {210, 205, 205}, {227, 218, 208}}};
constexpr Rgb kBuildingEdge{193, 181, 171};
constexpr Rgb kPark{205, 232, 180};
constexpr Rgb kTree{140, 194, 118};
constexpr Rgb kTreeDark{112, 170, 96};
constexpr Rgb kQuay{140, 182, 199};
constexpr Rgb kWater{170, 211, 223};
constexpr Rgb kCasing{198, 190, 180};
constexpr Rgb kStreet{255, 255, 255};
constexpr Rgb kMainCasing{204, 192, 128};
constexpr Rgb kMain{248, 245, 192};
constexpr Rgb kAvenueCasing{216, 152, 98};
constexpr Rgb kAvenue{252, 214, 164};
constexpr Rgb kPaving{239, 230, 210};
constexpr Rgb kInk{52, 52, 52};
constexpr Rgb kBlockInk{112, 98, 88};
constexpr Rgb kDistrictInk{120, 96, 84};
constexpr Rgb kRiverInk{46, 96, 138};
constexpr Rgb kHalo{255, 255, 255};
constexpr std::array<Rgb, 4> kClusters{
    {{200, 40, 60}, {110, 60, 170}, {20, 120, 150}, {220, 110, 20}}};
}  // namespace palette

/// Uniform random numbers from a fixed-seed std::mt19937, converted by hand so the sequence
/// does not depend on the standard library's distributions.
class Random {
 public:
  explicit Random(std::uint32_t seed) : engine_(seed) {}
  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * (engine_() / 4294967296.0); }
  /// Uniform integer in [lo, hi].
  int integer(int lo, int hi) { return lo + static_cast<int>(uniform(0, hi - lo + 1)); }
  bool chance(double p) { return uniform(0, 1) < p; }

 private:
  std::mt19937 engine_;
};

/// The kCanvas x kCanvas supersampled RGB canvas. Drawing calls take output pixels; a
/// subsample is covered when its centre is inside the shape.
class Canvas {
 public:
  Canvas() : samples_(std::size_t{kCanvas} * kCanvas, palette::kLand) {}

  /// Fills a simple or self-intersecting polygon (even-odd rule), vertices in output pixels.
  void fill_polygon(const std::vector<Vec2>& polygon, Rgb color) {
    double top = polygon.front().y, bottom = top;
    for (const Vec2& p : polygon) {
      top = std::min(top, p.y);
      bottom = std::max(bottom, p.y);
    }
    std::vector<double> crossings;
    for (int row = first_sample(top); row < first_sample(bottom); ++row) {
      const double y = (row + 0.5) / kSuper;
      crossings.clear();
      for (std::size_t k = 0; k < polygon.size(); ++k) {
        const Vec2 p = polygon[k], q = polygon[(k + 1) % polygon.size()];
        if ((p.y <= y) != (q.y <= y)) {
          crossings.push_back(p.x + (y - p.y) * (q.x - p.x) / (q.y - p.y));
        }
      }
      std::sort(crossings.begin(), crossings.end());
      for (std::size_t k = 0; k + 1 < crossings.size(); k += 2) {
        fill_span(row, crossings[k], crossings[k + 1], color);
      }
    }
  }

  void fill_rect(const Box& box, Rgb color) {
    fill_polygon({{box.x0, box.y0}, {box.x1, box.y0}, {box.x1, box.y1}, {box.x0, box.y1}}, color);
  }

  void fill_disk(Vec2 center, double radius, Rgb color) {
    for (int row = first_sample(center.y - radius); row < first_sample(center.y + radius); ++row) {
      const double dy = (row + 0.5) / kSuper - center.y;
      const double half = std::sqrt(std::max(0.0, radius * radius - dy * dy));
      fill_span(row, center.x - half, center.x + half, color);
    }
  }

  /// Strokes the segment a-b `width` pixels wide with round caps (so polylines join smoothly).
  void stroke(Vec2 a, Vec2 b, double width, Rgb color) {
    const Vec2 d = b - a;
    if (length(d) > 0) {
      const Vec2 n = (0.5 * width / length(d)) * Vec2{-d.y, d.x};
      fill_polygon({a + n, b + n, b - n, a - n}, color);
    }
    fill_disk(a, 0.5 * width, color);
    fill_disk(b, 0.5 * width, color);
  }

  /// Box-filters the canvas to kSize x kSize, row-major interleaved RGB bytes.
  std::vector<unsigned char> downsample() const {
    std::vector<unsigned char> rgb(std::size_t{kSize} * kSize * 3);
    for (int y = 0; y < kSize; ++y) {
      for (int x = 0; x < kSize; ++x) {
        std::array<int, 3> sum{};
        for (int sy = 0; sy < kSuper; ++sy) {
          for (int sx = 0; sx < kSuper; ++sx) {
            const Rgb& s = samples_[std::size_t{kCanvas} * (y * kSuper + sy) + x * kSuper + sx];
            sum[0] += s.r;
            sum[1] += s.g;
            sum[2] += s.b;
          }
        }
        for (int c = 0; c < 3; ++c) {
          rgb[(std::size_t{kSize} * y + x) * 3 + c] =
              static_cast<unsigned char>((sum[c] + kSuper * kSuper / 2) / (kSuper * kSuper));
        }
      }
    }
    return rgb;
  }

 private:
  /// Index of the first subsample (row or column) whose centre is at or after `v` output
  /// pixels, clamped to [0, kCanvas].
  static int first_sample(double v) {
    return static_cast<int>(std::clamp(std::ceil(v * kSuper - 0.5), 0.0, double{kCanvas}));
  }

  /// Fills the subsamples of `row` whose centres lie in [x0, x1), output pixels.
  void fill_span(int row, double x0, double x1, Rgb color) {
    const auto line = samples_.begin() + std::ptrdiff_t{kCanvas} * row;
    const int begin = first_sample(x0), end = first_sample(x1);
    if (begin < end) std::fill(line + begin, line + end, color);
  }

  std::vector<Rgb> samples_;  // kCanvas x kCanvas, row-major
};

/// A text label drawn with stb_easy_font's stroke font (capitals are 7 font units tall, strokes
/// 1 unit wide), centred on `center` and rotated by `angle`, with a halo under it.
struct Label {
  std::string text;
  Vec2 center;       // output pixels
  double scale;      // output pixels per font unit
  double angle = 0;  // radians, clockwise on screen
  Rgb ink = palette::kInk;
  double spacing = 0;  // extra font units between letters
};

constexpr double kHalo = 0.9;  // halo width around every stroke, font units
// Scales of the small labels, output pixels per font unit: capitals 4.6 and 4.3 pixels tall, a
// blur at 1x that magnification turns into text.
constexpr double kStreetLabel = 0.66;
constexpr double kNumberLabel = 0.62;

/// The strokes of `text` as axis-aligned boxes in font units (y down, origin top-left).
std::vector<Box> font_strokes(const Label& label) {
  stb_easy_font_spacing(static_cast<float>(label.spacing));
  std::string text = label.text;  // stb_easy_font takes a mutable char*
  // One quad is 64 bytes and no glyph has more than 16 strokes: 1 KiB per character suffices.
  std::vector<char> vertices(text.size() * 1024 + 64);
  const int quads = stb_easy_font_print(0, 0, text.data(), nullptr, vertices.data(),
                                        static_cast<int>(vertices.size()));
  std::vector<Box> strokes;
  for (int q = 0; q < quads; ++q) {
    Box box{1e9, 1e9, -1e9, -1e9};
    for (int v = 0; v < 4; ++v) {
      float xy[2];  // a vertex is x, y, z (floats) then 4 colour bytes
      std::memcpy(xy, vertices.data() + 64 * q + 16 * v, sizeof xy);
      box = {std::min<double>(box.x0, xy[0]), std::min<double>(box.y0, xy[1]),
             std::max<double>(box.x1, xy[0]), std::max<double>(box.y1, xy[1])};
    }
    strokes.push_back(box);
  }
  return strokes;
}

/// Places labels on the canvas, skipping any that would overlap one already placed.
class LabelLayer {
 public:
  explicit LabelLayer(Canvas& canvas) : canvas_(canvas) {}

  /// Keeps labels out of `box` (output pixels).
  void reserve(const Box& box) { taken_.push_back(box); }

  /// Draws `label` unless its bounding box overlaps a placed label, a reserved box or the image
  /// border.
  void place(const Label& label) {
    const std::vector<Box> strokes = font_strokes(label);
    Box extent = strokes.front();
    for (const Box& s : strokes) {
      extent = {std::min(extent.x0, s.x0), std::min(extent.y0, s.y0), std::max(extent.x1, s.x1),
                std::max(extent.y1, s.y1)};
    }
    const Vec2 mid{0.5 * (extent.x0 + extent.x1), 0.5 * (extent.y0 + extent.y1)};
    const Vec2 u = direction(label.angle), v = direction(label.angle + 0.5 * kPi);
    const double half_w = label.scale * (0.5 * (extent.x1 - extent.x0) + kHalo) + 1;
    const double half_h = label.scale * (0.5 * (extent.y1 - extent.y0) + kHalo) + 1;
    const Vec2 half{std::abs(u.x) * half_w + std::abs(v.x) * half_h,
                    std::abs(u.y) * half_w + std::abs(v.y) * half_h};
    const Box bounds{label.center.x - half.x, label.center.y - half.y, label.center.x + half.x,
                     label.center.y + half.y};
    if (bounds.x0 < 0 || bounds.y0 < 0 || bounds.x1 > kSize || bounds.y1 > kSize) return;
    for (const Box& t : taken_) {
      if (t.overlaps(bounds)) return;
    }
    taken_.push_back(bounds);

    const auto to_canvas = [&](double fx, double fy) {
      return label.center + (label.scale * (fx - mid.x)) * u + (label.scale * (fy - mid.y)) * v;
    };
    for (const double grow : {kHalo, 0.0}) {
      const Rgb color = grow > 0 ? palette::kHalo : label.ink;
      for (const Box& s : strokes) {
        canvas_.fill_polygon(
            {to_canvas(s.x0 - grow, s.y0 - grow), to_canvas(s.x1 + grow, s.y0 - grow),
             to_canvas(s.x1 + grow, s.y1 + grow), to_canvas(s.x0 - grow, s.y1 + grow)},
            color);
      }
    }
  }

 private:
  Canvas& canvas_;
  std::vector<Box> taken_;
};

/// The river: its centre line is the graph y = center(x), output pixels.
struct River {
  double center(double x) const {
    return 600 + 105 * std::sin(2 * kPi * x / 900 + 0.6) + 32 * std::sin(2 * kPi * x / 310 + 1.9);
  }
  double slope(double x) const {
    return 105 * 2 * kPi / 900 * std::cos(2 * kPi * x / 900 + 0.6) +
           32 * 2 * kPi / 310 * std::cos(2 * kPi * x / 310 + 1.9);
  }
  double half_width(double x) const { return 16 + 4 * std::sin(2 * kPi * x / 380 + 0.3); }
  /// Unit normal of the centre line at abscissa x (pointing down-ish).
  Vec2 normal(double x) const {
    const double s = slope(x);
    return (1 / std::hypot(1.0, s)) * Vec2{-s, 1};
  }
  /// Approximate distance from p to the water's edge (negative in the water), pixels.
  double distance(Vec2 p) const {
    return std::abs(p.y - center(p.x)) / std::hypot(1.0, slope(p.x)) - half_width(p.x);
  }
};

/// A straight avenue from `a` to `b` (both outside the image), output pixels.
struct Avenue {
  Vec2 a, b;
  std::string name;
  double distance(Vec2 p) const {
    const Vec2 d = b - a;
    return std::abs(d.x * (p.y - a.y) - d.y * (p.x - a.x)) / length(d);
  }
};

struct Plaza {
  Vec2 center;
  double radius;  // pixels
  std::string name;
};

/// Nodes joined by links, drawn over the map like a transit network.
struct Cluster {
  std::vector<Vec2> nodes;
  std::vector<std::array<int, 2>> links;  // indices into nodes
  Rgb color;
};

/// Everything placed on the map, output pixels.
struct City {
  std::vector<double> columns;  // x of the north-south streets, increasing
  std::vector<double> rows;     // y of the east-west streets, increasing
  River river;
  std::vector<Avenue> avenues;
  std::vector<Plaza> plazas;
  std::vector<Cluster> clusters;
};

constexpr double kStreetWidth = 4.5;  // minor street, pixels
constexpr double kMainWidth = 7;      // every fourth street
constexpr double kAvenueWidth = 9;
constexpr double kCasing = 1.1;  // casing on each side of a street, pixels
constexpr double kClusterRadius = 70;

bool is_main_street(std::size_t index) { return index % 4 == 2; }
double street_width(std::size_t index) { return is_main_street(index) ? kMainWidth : kStreetWidth; }

std::vector<double> street_positions(Random& random, double min_gap, double max_gap) {
  std::vector<double> positions;
  for (double p = -random.uniform(0, min_gap); p < kSize + max_gap;
       p += random.uniform(min_gap, max_gap)) {
    positions.push_back(p);
  }
  return positions;
}

/// The nodes of a cluster: up to `count` points in a disk, at least 15 pixels apart.
std::vector<Vec2> cluster_nodes(Random& random, Vec2 center, int count) {
  std::vector<Vec2> nodes;
  for (int attempt = 0; attempt < 400 && static_cast<int>(nodes.size()) < count; ++attempt) {
    const double r = kClusterRadius * std::sqrt(random.uniform(0, 1));
    const Vec2 p = center + r * direction(random.uniform(0, 2 * kPi));
    if (std::all_of(nodes.begin(), nodes.end(), [&](Vec2 q) { return length(p - q) > 15; })) {
      nodes.push_back(p);
    }
  }
  return nodes;
}

/// Links: a minimum spanning tree (Prim), plus a few short extra links that close loops.
std::vector<std::array<int, 2>> cluster_links(Random& random, const std::vector<Vec2>& nodes) {
  const int n = static_cast<int>(nodes.size());
  std::vector<std::array<int, 2>> links;
  std::vector<bool> in_tree(n, false);
  in_tree[0] = true;
  for (int added = 1; added < n; ++added) {
    std::array<int, 2> best{0, 0};
    double best_length = 1e9;
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        if (in_tree[i] && !in_tree[j] && length(nodes[i] - nodes[j]) < best_length) {
          best = {i, j};
          best_length = length(nodes[i] - nodes[j]);
        }
      }
    }
    in_tree[best[1]] = true;
    links.push_back(best);
  }
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      const bool linked = std::any_of(links.begin(), links.end(), [&](const std::array<int, 2>& l) {
        return (l[0] == i && l[1] == j) || (l[0] == j && l[1] == i);
      });
      if (!linked && length(nodes[i] - nodes[j]) < 38 && random.chance(0.35))
        links.push_back({i, j});
    }
  }
  return links;
}

City lay_out(Random& random) {
  City city;
  city.columns = street_positions(random, 50, 66);
  city.rows = street_positions(random, 38, 50);
  city.avenues = {{{-40, 150}, {1064, 930}, "BROADWAY"},
                  {{-40, 900}, {760, -40}, "LENS BOULEVARD"},
                  {{430, 1064}, {1064, 430}, "FOCUS AVENUE"}};

  const std::array<Vec2, 4> hubs{{{165, 175}, {850, 215}, {175, 865}, {790, 875}}};
  for (std::size_t c = 0; c < hubs.size(); ++c) {
    Cluster cluster{
        cluster_nodes(random, hubs[c], random.integer(10, 14)), {}, palette::kClusters[c]};
    cluster.links = cluster_links(random, cluster.nodes);
    city.clusters.push_back(cluster);
  }

  // A roundabout where the first two avenues cross, then squares at free street crossings.
  const Avenue& a = city.avenues[0];
  const Avenue& b = city.avenues[1];
  const Vec2 da = a.b - a.a, db = b.b - b.a, ab = b.a - a.a;
  const double t = (ab.x * db.y - ab.y * db.x) / (da.x * db.y - da.y * db.x);
  city.plazas.push_back({a.a + t * da, 30, "STAR CIRCLE"});
  const std::array<const char*, 5> names{"MARKET SQ", "UNION SQ", "CIVIC PLAZA", "FOUNTAIN SQ",
                                         "LIBERTY SQ"};
  for (int attempt = 0; attempt < 500 && city.plazas.size() < 1 + names.size(); ++attempt) {
    const Vec2 p{city.columns[random.integer(1, static_cast<int>(city.columns.size()) - 2)],
                 city.rows[random.integer(1, static_cast<int>(city.rows.size()) - 2)]};
    const double r = random.uniform(18, 26);
    const bool free = p.x > r + 30 && p.y > r + 30 && p.x < kSize - r - 30 &&
                      p.y < kSize - r - 30 && city.river.distance(p) > r + 25 &&
                      std::all_of(city.avenues.begin(), city.avenues.end(),
                                  [&](const Avenue& v) { return v.distance(p) > r + 16; }) &&
                      std::all_of(city.plazas.begin(), city.plazas.end(),
                                  [&](const Plaza& q) { return length(q.center - p) > 180; }) &&
                      std::all_of(hubs.begin(), hubs.end(),
                                  [&](Vec2 h) { return length(h - p) > kClusterRadius + r + 20; });
    if (free) city.plazas.push_back({p, r, names[city.plazas.size() - 1]});
  }
  return city;
}

/// A block of small buildings in two rows (front and back), or a single row if it is shallow.
void paint_buildings(const Box& block, Random& random, Canvas& canvas) {
  canvas.fill_rect(block, palette::kYard);
  const double height = block.y1 - block.y0;
  const int rows = height > 16 ? 2 : 1;
  for (int row = 0; row < rows; ++row) {
    const double depth = rows == 2 ? random.uniform(0.32, 0.46) * height : height;
    const double y0 = row == 0 ? block.y0 : block.y1 - depth;
    for (double x = block.x0; x < block.x1 - 2;) {
      const double width = std::min(random.uniform(5, 13), block.x1 - x);
      const Box building{x + 0.4, y0 + 0.4, x + width - 0.4, y0 + depth - 0.4};
      canvas.fill_rect(building, palette::kBuildingEdge);
      canvas.fill_rect({building.x0 + 0.6, building.y0 + 0.6, building.x1 - 0.6, building.y1 - 0.6},
                       palette::kBuildings[random.integer(0, 3)]);
      x += width;
    }
  }
}

void paint_park(const Box& block, Random& random, Canvas& canvas) {
  canvas.fill_rect(block, palette::kPark);
  const double area = (block.x1 - block.x0) * (block.y1 - block.y0);
  for (int k = 0; k < static_cast<int>(area / 30); ++k) {
    const Vec2 p{random.uniform(block.x0 + 2, block.x1 - 2),
                 random.uniform(block.y0 + 2, block.y1 - 2)};
    canvas.fill_disk(p, random.uniform(1.1, 2.3),
                     random.chance(0.5) ? palette::kTree : palette::kTreeDark);
  }
}

/// Blocks between the streets: mostly buildings, some parks.
void paint_blocks(const City& city, Random& random, Canvas& canvas) {
  for (std::size_t i = 0; i + 1 < city.columns.size(); ++i) {
    for (std::size_t j = 0; j + 1 < city.rows.size(); ++j) {
      const Box block{city.columns[i] + 0.5 * street_width(i) + kCasing + 1.2,
                      city.rows[j] + 0.5 * street_width(j) + kCasing + 1.2,
                      city.columns[i + 1] - 0.5 * street_width(i + 1) - kCasing - 1.2,
                      city.rows[j + 1] - 0.5 * street_width(j + 1) - kCasing - 1.2};
      if (random.chance(0.09)) {
        paint_park(block, random, canvas);
      } else {
        paint_buildings(block, random, canvas);
      }
    }
  }
}

/// The river with a green promenade, a quay edge and trees along both banks.
void paint_river(const City& city, Random& random, Canvas& canvas) {
  const River& river = city.river;
  const auto band = [&](double extra) {
    std::vector<Vec2> polygon;
    for (double x = -40; x <= kSize + 40; x += 2) {
      polygon.push_back(Vec2{x, river.center(x)} - (river.half_width(x) + extra) * river.normal(x));
    }
    for (double x = kSize + 40; x >= -40; x -= 2) {
      polygon.push_back(Vec2{x, river.center(x)} + (river.half_width(x) + extra) * river.normal(x));
    }
    return polygon;
  };
  canvas.fill_polygon(band(8), palette::kPark);
  for (double x = -10; x < kSize + 10; x += 6) {
    for (const double side : {-1.0, 1.0}) {
      if (random.chance(0.7)) {
        canvas.fill_disk(
            Vec2{x, river.center(x)} + (side * (river.half_width(x) + 5)) * river.normal(x),
            random.uniform(1.2, 2), palette::kTreeDark);
      }
    }
  }
  canvas.fill_polygon(band(1.2), palette::kQuay);
  canvas.fill_polygon(band(0), palette::kWater);
}

/// Streets as casing then fill; the river, painted afterwards, cuts them; bridges and avenues
/// are painted over it.
void paint_streets(const City& city, Random& random, Canvas& canvas) {
  const auto street = [&](std::size_t index, bool vertical, double along0, double along1,
                          bool casing) {
    const double at = vertical ? city.columns[index] : city.rows[index];
    const Vec2 a = vertical ? Vec2{at, along0} : Vec2{along0, at};
    const Vec2 b = vertical ? Vec2{at, along1} : Vec2{along1, at};
    const double width = street_width(index) + (casing ? 2 * kCasing : 0);
    const bool main = is_main_street(index);
    canvas.stroke(a, b, width,
                  casing ? (main ? palette::kMainCasing : palette::kCasing)
                         : (main ? palette::kMain : palette::kStreet));
  };
  for (const bool casing : {true, false}) {
    for (const bool main : {false, true}) {
      for (std::size_t i = 0; i < city.columns.size(); ++i) {
        if (is_main_street(i) == main) street(i, true, -20, kSize + 20, casing);
      }
      for (std::size_t j = 0; j < city.rows.size(); ++j) {
        if (is_main_street(j) == main) street(j, false, -20, kSize + 20, casing);
      }
    }
  }

  paint_river(city, random, canvas);

  for (const bool casing : {true, false}) {
    for (std::size_t i = 0; i < city.columns.size(); i += 3) {
      const double x = city.columns[i];
      const double reach = city.river.half_width(x) * std::hypot(1.0, city.river.slope(x)) + 6;
      street(i, true, city.river.center(x) - reach, city.river.center(x) + reach, casing);
    }
    for (const Avenue& avenue : city.avenues) {
      canvas.stroke(avenue.a, avenue.b, kAvenueWidth + (casing ? 2 * kCasing : 0),
                    casing ? palette::kAvenueCasing : palette::kAvenue);
    }
  }
}

/// Round plazas: paving, a lawn ring crossed by paths, trees and a fountain.
void paint_plazas(const City& city, Canvas& canvas) {
  for (const Plaza& plaza : city.plazas) {
    const double r = plaza.radius;
    canvas.fill_disk(plaza.center, r + kCasing, palette::kCasing);
    canvas.fill_disk(plaza.center, r, palette::kPaving);
    canvas.fill_disk(plaza.center, 0.8 * r, palette::kPark);
    for (int k = 0; k < 8; ++k) {
      const Vec2 d = direction(k * kPi / 4);
      canvas.stroke(plaza.center + (0.45 * r) * d, plaza.center + r * d, 1.4, palette::kPaving);
    }
    for (int k = 0; k < 16; ++k) {
      canvas.fill_disk(plaza.center + (0.64 * r) * direction((k + 0.5) * kPi / 8), 1.5,
                       palette::kTreeDark);
    }
    canvas.fill_disk(plaza.center, 0.45 * r, palette::kPaving);
    canvas.fill_disk(plaza.center, 0.3 * r, palette::kQuay);
    canvas.fill_disk(plaza.center, 0.3 * r - 0.8, palette::kWater);
    canvas.fill_disk(plaza.center, 1.2, palette::kQuay);
  }
}

void paint_clusters(const City& city, Canvas& canvas) {
  for (const Cluster& cluster : city.clusters) {
    for (const auto& link : cluster.links) {
      canvas.stroke(cluster.nodes[link[0]], cluster.nodes[link[1]], 3.4, palette::kHalo);
    }
    for (const auto& link : cluster.links) {
      canvas.stroke(cluster.nodes[link[0]], cluster.nodes[link[1]], 1.6, cluster.color);
    }
    for (std::size_t k = 0; k < cluster.nodes.size(); ++k) {
      const double r = k == 0 ? 5.0 : 3.6;
      canvas.fill_disk(cluster.nodes[k], r + 0.8, palette::kHalo);
      canvas.fill_disk(cluster.nodes[k], r, cluster.color);
      canvas.fill_disk(cluster.nodes[k], 0.5 * r, palette::kHalo);
    }
  }
}

/// "1ST", "2ND", "3RD", "4TH", ..., "11TH", ..., "21ST", ...
std::string ordinal(int n) {
  const int tens = n % 100, units = n % 10;
  const char* suffix = (tens >= 11 && tens <= 13) ? "TH"
                       : units == 1               ? "ST"
                       : units == 2               ? "ND"
                       : units == 3               ? "RD"
                                                  : "TH";
  return std::to_string(n) + suffix;
}

/// The scale bar and north arrow in the bottom-left corner, on a white panel.
void paint_furniture(Canvas& canvas, LabelLayer& labels) {
  const Box panel{12, 962, 214, 1012};
  labels.reserve(panel);
  canvas.fill_rect(panel, palette::kCasing);
  canvas.fill_rect({panel.x0 + 1, panel.y0 + 1, panel.x1 - 1, panel.y1 - 1}, palette::kHalo);
  for (int k = 0; k < 4; ++k) {
    const Box segment{24.0 + 32 * k, 980, 56.0 + 32 * k, 985};
    canvas.fill_rect(segment, palette::kInk);
    if (k % 2 == 1) {
      canvas.fill_rect({segment.x0, segment.y0 + 1, segment.x1, segment.y1 - 1}, palette::kHalo);
    }
  }
  LabelLayer panel_labels(canvas);  // its own layer: the panel is reserved in `labels`
  for (int k = 0; k <= 4; k += 2) {
    panel_labels.place({std::to_string(100 * k) + (k == 4 ? " M" : ""),
                        {24.0 + 32 * k + (k == 4 ? 6 : 0), 995},
                        0.8});
  }
  canvas.fill_polygon({{192, 970}, {199, 992}, {192, 987}, {185, 992}}, palette::kInk);
  panel_labels.place({"N", {192, 1003}, 1.0});
}

/// Every label, most important first so that they win where labels would overlap.
void paint_labels(const City& city, Random& random, Canvas& canvas) {
  LabelLayer labels(canvas);
  paint_furniture(canvas, labels);

  const std::array<std::pair<const char*, Vec2>, 6> districts{{{"OLD TOWN", {470, 300}},
                                                               {"RIVERSIDE", {620, 445}},
                                                               {"NORTH HILL", {560, 90}},
                                                               {"HARBOR", {880, 470}},
                                                               {"WEST END", {120, 560}},
                                                               {"EAST VILLAGE", {560, 780}}}};
  for (const auto& [name, at] : districts) {
    labels.place({name, at, 2.2, 0, palette::kDistrictInk, 1.5});
  }

  for (const double x : {300.0, 720.0, 120.0, 900.0}) {
    labels.place({"GEO RIVER",
                  {x, city.river.center(x)},
                  1.1,
                  std::atan(city.river.slope(x)),
                  palette::kRiverInk,
                  0.5});
  }

  for (const Plaza& plaza : city.plazas) {
    labels.place({plaza.name, plaza.center + Vec2{0, plaza.radius + 7}, 0.75});
    const double r = plaza.radius + kCasing;
    labels.reserve(
        {plaza.center.x - r, plaza.center.y - r, plaza.center.x + r, plaza.center.y + r});
  }

  for (const Cluster& cluster : city.clusters) {
    for (const Vec2& node : cluster.nodes) {
      labels.reserve({node.x - 5, node.y - 5, node.x + 5, node.y + 5});
    }
  }
  for (std::size_t c = 0; c < city.clusters.size(); ++c) {
    const Cluster& cluster = city.clusters[c];
    const Rgb ink{static_cast<std::uint8_t>(cluster.color.r * 3 / 4),
                  static_cast<std::uint8_t>(cluster.color.g * 3 / 4),
                  static_cast<std::uint8_t>(cluster.color.b * 3 / 4)};
    for (std::size_t k = 0; k < cluster.nodes.size(); ++k) {
      const std::string name = k == 0 ? std::string(1, static_cast<char>('A' + c)) + " HUB"
                                      : std::to_string(10 * (c + 1) + k);
      labels.place(
          {name, cluster.nodes[k] + Vec2{0, k == 0 ? 12.0 : 9.0}, k == 0 ? 0.9 : 0.62, 0, ink});
    }
  }

  for (const Avenue& avenue : city.avenues) {
    const Vec2 d = avenue.b - avenue.a;
    for (double t = 0.1; t < 1; t += 0.11) {
      labels.place({avenue.name, avenue.a + t * d, 0.8, std::atan2(d.y, d.x)});
    }
  }

  const std::array<const char*, 30> trees{
      "ELM ST",     "OAK ST",     "PINE ST",   "MAPLE ST",  "CEDAR ST",    "ASH ST",
      "BIRCH ST",   "WALNUT ST",  "CHERRY ST", "WILLOW ST", "HAZEL ST",    "LARCH ST",
      "SPRUCE ST",  "ALDER ST",   "POPLAR ST", "LINDEN ST", "CHESTNUT ST", "ROWAN ST",
      "CYPRESS ST", "JUNIPER ST", "HOLLY ST",  "LAUREL ST", "BEECH ST",    "HICKORY ST",
      "ACACIA ST",  "SEQUOIA ST", "FIR ST",    "YEW ST",    "MYRTLE ST",   "OLIVE ST"};
  for (std::size_t j = 0; j < city.rows.size(); ++j) {
    for (std::size_t i = j % 2; i + 1 < city.columns.size(); i += 2) {
      const Vec2 at{0.5 * (city.columns[i] + city.columns[i + 1]), city.rows[j]};
      if (city.river.distance(at) > 4) {
        labels.place({trees[j % trees.size()], at, kStreetLabel});
      }
    }
  }
  for (std::size_t i = 0; i < city.columns.size(); ++i) {
    for (std::size_t j = i % 2; j + 1 < city.rows.size(); j += 2) {
      const Vec2 at{city.columns[i], 0.5 * (city.rows[j] + city.rows[j + 1])};
      if (city.river.distance(at) > 4) {
        labels.place({ordinal(static_cast<int>(i) + 1) + " AVE", at, kStreetLabel, -0.5 * kPi});
      }
    }
  }

  for (std::size_t i = 0; i + 1 < city.columns.size(); ++i) {
    for (std::size_t j = 0; j + 1 < city.rows.size(); ++j) {
      const Vec2 at{0.5 * (city.columns[i] + city.columns[i + 1]),
                    0.5 * (city.rows[j] + city.rows[j + 1])};
      if (city.river.distance(at) > 12 && random.chance(0.5)) {
        labels.place(
            {std::to_string(100 * (j + 1) + 2 * i), at, kNumberLabel, 0, palette::kBlockInk});
      }
    }
  }
}

Canvas draw_city() {
  Random random(20240611);
  const City city = lay_out(random);
  Canvas canvas;
  paint_blocks(city, random, canvas);
  paint_streets(city, random, canvas);
  paint_plazas(city, canvas);
  paint_clusters(city, canvas);
  paint_labels(city, random, canvas);
  return canvas;
}

/// Encodes `rgb` (kSize x kSize) as PNG and writes it to `path` through a temporary file in the
/// same directory, so a failed run never leaves a partial image. Returns an error message, empty
/// on success.
std::string write_png(const std::string& path, const std::vector<unsigned char>& rgb) {
  std::vector<char> png;
  const auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<char>*>(context);
    out->insert(out->end(), static_cast<char*>(data), static_cast<char*>(data) + size);
  };
  if (!stbi_write_png_to_func(append, &png, kSize, kSize, 3, rgb.data(), kSize * 3)) {
    return "PNG encoding failed";
  }
  const std::string temporary = path + ".tmp";
  {
    std::ofstream file(temporary, std::ios::binary);
    file.write(png.data(), static_cast<std::streamsize>(png.size()));
    if (!file.flush()) {
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      return "cannot write " + temporary;
    }
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::filesystem::remove(temporary, error);
    return "cannot rename " + temporary + " to " + path;
  }
  return {};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2 || argv[1][0] == '-') {
    std::fprintf(stderr, "usage: make_demo_image OUTPUT.png\n");
    return 2;
  }
  const std::string error = write_png(argv[1], draw_city().downsample());
  if (!error.empty()) {
    std::fprintf(stderr, "make_demo_image: %s\n", error.c_str());
    return 1;
  }
  return 0;
}
