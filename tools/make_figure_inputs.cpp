// make_figure_inputs: draws the synthetic inputs scripts/reproduce_figures.sh uses to reproduce
// the paper's figures (the map is the bundled examples/demo.png):
//
//   grid.png   512 x 512   a regular grid of thin lines with a checker tint, the paper's test
//                          pattern for metrics and distortion (Fig. 6, Fig. 7)
//   graph.png  1024 x 1024 a node-link graph of "company relations": clusters of labelled nodes
//                          joined by edges, labels 6 pixels tall (Fig. 5)
//   text.png   1024 x 1024 a page of text in columns of small print under a large title (Fig. 5)
//
// Usage: make_figure_inputs OUTPUT_FOLDER
// Exit code 0 on success, 1 if a file cannot be written, 2 on bad usage.
//
// Deterministic: every random choice comes from a std::mt19937 with a fixed seed. Shapes are
// drawn hard-edged on a 3x3 supersampled canvas that is box-filtered down (antialiasing).

#include <stb_easy_font.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

namespace {

constexpr int kSuper = 3;  // subsamples per output pixel along each axis

struct Rgb {
  uint8_t r, g, b;
};

/// An RGB canvas in subsamples; coordinates given to the drawing calls are output pixels.
class Canvas {
 public:
  Canvas(int size, Rgb paper)
      : size_(size), side_(size * kSuper), pixels_(size_t(side_) * side_, paper) {}

  /// Fills the box [x0, x1) x [y0, y1) (output pixels).
  void box(double x0, double y0, double x1, double y1, Rgb colour) {
    const int i0 = std::max(0, int(std::lround(x0 * kSuper))),
              i1 = std::min(side_, int(std::lround(x1 * kSuper)));
    const int j0 = std::max(0, int(std::lround(y0 * kSuper))),
              j1 = std::min(side_, int(std::lround(y1 * kSuper)));
    for (int j = j0; j < j1; ++j)
      for (int i = i0; i < i1; ++i) pixels_[size_t(j) * side_ + i] = colour;
  }

  /// A disc of radius r around (x, y).
  void disc(double x, double y, double r, Rgb colour) {
    const double s = kSuper;
    for (int j = std::max(0, int((y - r) * s)); j < std::min(side_, int((y + r) * s) + 1); ++j)
      for (int i = std::max(0, int((x - r) * s)); i < std::min(side_, int((x + r) * s) + 1); ++i)
        if (std::hypot((i + 0.5) / s - x, (j + 0.5) / s - y) <= r)
          pixels_[size_t(j) * side_ + i] = colour;
  }

  /// A segment of the given width with round ends.
  void line(double x0, double y0, double x1, double y1, double width, Rgb colour) {
    const double s = kSuper, h = width / 2, dx = x1 - x0, dy = y1 - y0;
    const double length2 = std::max(dx * dx + dy * dy, 1e-12);
    for (int j = std::max(0, int((std::min(y0, y1) - h) * s));
         j < std::min(side_, int((std::max(y0, y1) + h) * s) + 1); ++j)
      for (int i = std::max(0, int((std::min(x0, x1) - h) * s));
           i < std::min(side_, int((std::max(x0, x1) + h) * s) + 1); ++i) {
        const double px = (i + 0.5) / s, py = (j + 0.5) / s;
        const double t = std::clamp(((px - x0) * dx + (py - y0) * dy) / length2, 0.0, 1.0);
        if (std::hypot(px - x0 - t * dx, py - y0 - t * dy) <= h)
          pixels_[size_t(j) * side_ + i] = colour;
      }
  }

  /// Text with stb_easy_font's stroke font, top-left at (x, y), `scale` output pixels per font
  /// unit (capitals are 7 units tall). Returns the width drawn, output pixels.
  double text(double x, double y, const std::string& text, double scale, Rgb colour) {
    std::string copy = text;
    std::vector<char> buffer(copy.size() * 16 * 64 + 64);
    stb_easy_font_spacing(0);
    const int quads =
        stb_easy_font_print(0, 0, copy.data(), nullptr, buffer.data(), int(buffer.size()));
    for (int q = 0; q < quads; ++q) {
      float lo[2] = {1e9f, 1e9f}, hi[2] = {-1e9f, -1e9f};
      for (int v = 0; v < 4; ++v) {
        float xy[2];
        std::memcpy(xy, buffer.data() + 64 * q + 16 * v, sizeof xy);
        for (int k = 0; k < 2; ++k) {
          lo[k] = std::min(lo[k], xy[k]);
          hi[k] = std::max(hi[k], xy[k]);
        }
      }
      box(x + lo[0] * scale, y + lo[1] * scale, x + hi[0] * scale, y + hi[1] * scale, colour);
    }
    return stb_easy_font_width(copy.data()) * scale;
  }

  /// Box-filters the canvas down and writes it as PNG; false on failure.
  bool save(const std::string& path) const {
    std::vector<uint8_t> out(size_t(size_) * size_ * 3);
    for (int y = 0; y < size_; ++y)
      for (int x = 0; x < size_; ++x) {
        int sum[3] = {0, 0, 0};
        for (int j = 0; j < kSuper; ++j)
          for (int i = 0; i < kSuper; ++i) {
            const Rgb& p = pixels_[size_t(y * kSuper + j) * side_ + x * kSuper + i];
            sum[0] += p.r;
            sum[1] += p.g;
            sum[2] += p.b;
          }
        for (int c = 0; c < 3; ++c)
          out[(size_t(y) * size_ + x) * 3 + c] =
              uint8_t((sum[c] + kSuper * kSuper / 2) / (kSuper * kSuper));
      }
    return stbi_write_png(path.c_str(), size_, size_, 3, out.data(), size_ * 3) != 0;
  }

 private:
  int size_, side_;
  std::vector<Rgb> pixels_;
};

/// Thin grid lines every 16 px, thicker every 64, on a faint checker of 64 px squares.
Canvas grid_image() {
  constexpr int kSize = 512;
  Canvas c(kSize, {255, 255, 255});
  for (int y = 0; y < kSize; y += 64)
    for (int x = 0; x < kSize; x += 64)
      if ((x / 64 + y / 64) % 2 == 0) c.box(x, y, x + 64, y + 64, {228, 236, 248});
  for (int k = 0; k <= kSize; k += 16) {
    const double width = k % 64 == 0 ? 2.0 : 1.0;
    const Rgb ink = k % 64 == 0 ? Rgb{30, 40, 90} : Rgb{110, 120, 160};
    c.box(k - width / 2, 0, k + width / 2, kSize, ink);
    c.box(0, k - width / 2, kSize, k + width / 2, ink);
  }
  return c;
}

/// Clusters of labelled nodes; edges join near nodes inside a cluster and a few across.
Canvas graph_image() {
  constexpr int kSize = 1024;
  Canvas c(kSize, {250, 250, 246});
  std::mt19937 random(2013);
  std::uniform_real_distribution<double> unit(0, 1);
  std::normal_distribution<double> spread(0, 1);
  struct Node {
    double x, y, r;
    int cluster;
  };
  std::vector<Node> nodes;
  const Rgb palette[] = {{200, 70, 60},  {60, 120, 200}, {60, 160, 90},
                         {190, 140, 40}, {140, 80, 180}, {40, 150, 160}};
  // Nine clusters on a jittered 3 x 3 layout, so the graph fills the page.
  for (int k = 0; k < 9; ++k) {
    const double cx = 190 + 320 * (k % 3) + 60 * spread(random);
    const double cy = 210 + 300 * (k / 3) + 50 * spread(random);
    const double sigma = 40 + 30 * unit(random);
    const int count = 12 + int(16 * unit(random));
    for (int i = 0; i < count; ++i) {
      const double x = std::clamp(cx + sigma * spread(random), 20.0, kSize - 20.0);
      const double y = std::clamp(cy + sigma * spread(random), 70.0, kSize - 20.0);
      nodes.push_back({x, y, 4 + 5 * unit(random) * unit(random), k});
    }
  }
  // Edges first, under the nodes.
  for (size_t i = 0; i < nodes.size(); ++i)
    for (size_t j = i + 1; j < nodes.size(); ++j) {
      const double d = std::hypot(nodes[i].x - nodes[j].x, nodes[i].y - nodes[j].y);
      const bool same = nodes[i].cluster == nodes[j].cluster;
      if ((same && d < 70 && unit(random) < 0.55) || (!same && d < 260 && unit(random) < 0.02))
        c.line(nodes[i].x, nodes[i].y, nodes[j].x, nodes[j].y, same ? 0.7 : 0.5,
               same ? Rgb{150, 150, 160} : Rgb{190, 170, 170});
    }
  for (size_t i = 0; i < nodes.size(); ++i) {
    const Node& n = nodes[i];
    c.disc(n.x, n.y, n.r + 1.2, {40, 40, 40});
    c.disc(n.x, n.y, n.r, palette[n.cluster % 6]);
    // Company codes, 6 pixels tall: readable at 1x, a blur when the page is shown small, readable
    // again under a lens.
    const std::string label = std::string(1, char('A' + n.cluster)) + std::to_string(100 + int(i));
    c.text(n.x + n.r + 2, n.y - 3.5, label, 0.85, {50, 50, 50});
  }
  c.text(24, 20, "COMPANY RELATIONS", 3, {30, 30, 30});
  return c;
}

/// A title and three columns of small print made of pseudo-words.
Canvas text_image() {
  constexpr int kSize = 1024;
  Canvas c(kSize, {252, 250, 244});
  std::mt19937 random(1968);
  std::uniform_int_distribution<int> length(2, 9), letter(0, 25), words_per_paragraph(40, 120);
  const Rgb ink = {25, 25, 30};
  c.text(40, 30, "THE GEOMETRIC LENS GAZETTE", 4, ink);
  c.text(40, 68, "Vol. 12  -  focus and context, all the news that fits the screen", 1.4,
         {90, 90, 90});
  c.box(40, 90, kSize - 40, 92, ink);
  const double scale = 0.8, line_height = 12 * scale + 2, column_width = 300, gap = 22;
  for (int column = 0; column < 3; ++column) {
    const double left = 40 + column * (column_width + gap);
    double y = 108;
    while (y < kSize - 40) {
      // One paragraph: a bold-ish heading line, then words filled into lines.
      std::string heading;
      for (int k = 0; k < 3; ++k) {
        for (int i = length(random); i > 0; --i) heading += char('A' + letter(random));
        heading += ' ';
      }
      c.text(left, y, heading, 1.1, ink);
      y += 12 * 1.1 + 3;
      std::string line;
      for (int w = words_per_paragraph(random); w > 0 && y < kSize - 40; --w) {
        std::string word;
        for (int i = length(random); i > 0; --i) word += char('a' + letter(random));
        const std::string candidate = line.empty() ? word : line + " " + word;
        stb_easy_font_spacing(0);
        std::string probe = candidate;
        if (stb_easy_font_width(probe.data()) * scale > column_width) {
          c.text(left, y, line, scale, ink);
          y += line_height;
          line = word;
        } else {
          line = candidate;
        }
      }
      if (!line.empty() && y < kSize - 40) c.text(left, y, line + ".", scale, ink);
      y += line_height + 8;
    }
  }
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_figure_inputs OUTPUT_FOLDER\n");
    return 2;
  }
  const std::filesystem::path folder = argv[1];
  if (!std::filesystem::is_directory(folder)) {
    std::fprintf(stderr, "make_figure_inputs: '%s' is not a folder\n", argv[1]);
    return 2;
  }
  const std::pair<const char*, Canvas> images[] = {
      {"grid.png", grid_image()}, {"graph.png", graph_image()}, {"text.png", text_image()}};
  for (const auto& [name, canvas] : images) {
    const std::string path = (folder / name).string();
    if (!canvas.save(path)) {
      std::fprintf(stderr, "make_figure_inputs: cannot write '%s'\n", path.c_str());
      return 1;
    }
  }
  return 0;
}
