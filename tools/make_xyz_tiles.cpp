// make_xyz_tiles: writes a folder of web-map tiles (z/x/y.png, 256 px, zooms 0 to MAX_ZOOM) of an
// imaginary country, drawn anew at every zoom as a web map is: roads and labels keep their size
// on screen, so each deeper zoom shows more of them (minor roads from zoom 2, streets from zoom
// 4, town names of rank r from zoom r). A lens over the tiles therefore shows in its focus names
// and roads that the context does not have.
//
// Usage: make_xyz_tiles OUTPUT_FOLDER [MAX_ZOOM]   (MAX_ZOOM in [0, 8], default 5)
// Exit code 0 on success, 1 if a tile cannot be written, 2 on bad usage.
//
// Deterministic: every random choice comes from a std::mt19937 with a fixed seed. Text is
// stb_easy_font's stroke font; every shape is drawn with its exact pixel coverage (area of the
// pixel it covers), so edges are antialiased.

#include <stb_easy_font.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "geolens/io/image.h"

namespace {

constexpr int kTile = 256;
constexpr double kPi = std::numbers::pi;

struct Rgb {
  double r, g, b;
};

constexpr Rgb kLand{242, 239, 233}, kPark{200, 228, 188}, kWater{160, 200, 226};
constexpr Rgb kMotorway{232, 146, 82}, kRoad{255, 255, 255}, kCasing{190, 186, 178};
constexpr Rgb kInk{40, 40, 48}, kHalo{255, 255, 255};

/// A box [x0, x1) x [y0, y1).
struct Box {
  double x0, y0, x1, y1;
};

/// A town: its place in the world ([0, 1)^2), its name, and the first zoom that shows it.
struct Town {
  double u, v;
  std::string name;
  int rank;
  std::vector<Box> strokes;  ///< font units, origin at the text's top left
  double width = 0;          ///< font units
};

/// Screen pixels per font unit of a label of `rank` (capitals are 7 font units tall).
double text_scale(int rank) { return rank == 0 ? 2.5 : rank == 1 ? 2.0 : 1.6; }

std::vector<Box> strokes_of(const std::string& text, double& width) {
  std::string mutable_text = text;  // stb_easy_font takes a char*
  std::vector<char> buffer(text.size() * 1024 + 64);
  const int quads =
      stb_easy_font_print(0, 0, mutable_text.data(), nullptr, buffer.data(), int(buffer.size()));
  std::vector<Box> boxes;
  width = 0;
  for (int q = 0; q < quads; ++q) {
    Box box{1e9, 1e9, -1e9, -1e9};
    for (int k = 0; k < 4; ++k) {
      float xy[2];  // a vertex: x, y, z as floats, then 4 colour bytes
      std::memcpy(xy, buffer.data() + 64 * q + 16 * k, sizeof xy);
      box = {std::min<double>(box.x0, xy[0]), std::min<double>(box.y0, xy[1]),
             std::max<double>(box.x1, xy[0]), std::max<double>(box.y1, xy[1])};
    }
    boxes.push_back(box);
    width = std::max(width, box.x1);
  }
  return boxes;
}

/// A made-up town name from syllables.
std::string town_name(std::mt19937& random) {
  static const char* kSyllables[] = {"BRA", "DOR", "KEL", "MAR", "VEN", "TOL", "RIS", "AN",
                                     "LU",  "SEN", "GAR", "OST", "FEN", "ILL", "NOR", "PE",
                                     "WIK", "HAL", "MO",  "TER", "ZA",  "QUI", "LEN", "BER"};
  const int count = 2 + int(random() % 2);
  std::string name;
  for (int i = 0; i < count; ++i) name += kSyllables[random() % std::size(kSyllables)];
  return name;
}

/// The label box of `town` at a zoom whose world is `side` pixels wide, in that zoom's pixels.
Box label_box(const Town& town, double side) {
  const double s = text_scale(town.rank), x = town.u * side, y = town.v * side;
  return {x - 4, y - 5 * s, x + 6 + (town.width + 1) * s, y + 5 * s};
}

bool overlap(const Box& a, const Box& b) {
  return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

/// Towns of ranks 0 to max_zoom, 12 2^rank candidates of each, kept only where their label would
/// not overlap one of the same or a lower rank at the zoom that first shows it, nor cross the
/// world's edge.
std::vector<Town> make_towns(int max_zoom) {
  std::mt19937 random(20240607);
  std::uniform_real_distribution<double> place(0.04, 0.90);
  std::vector<Town> towns;
  for (int rank = 0; rank <= max_zoom; ++rank) {
    const double side = kTile << rank;
    for (int i = 0; i < 12 << rank; ++i) {
      Town town;
      town.u = place(random);
      town.v = place(random);
      town.name = town_name(random);
      town.rank = rank;
      town.strokes = strokes_of(town.name, town.width);
      const Box box = label_box(town, side);
      if (box.x1 < side && std::none_of(towns.begin(), towns.end(), [&](const Town& other) {
            return overlap(box, label_box(other, side));
          }))
        towns.push_back(std::move(town));
    }
  }
  return towns;
}

/// The river's centre line v(u) and half width, world units.
double river(double u) {
  return 0.55 + 0.12 * std::sin(2 * kPi * (1.3 * u + 0.1)) + 0.03 * std::sin(2 * kPi * 4.7 * u);
}

/// Coverage in [0, 1] of a band of half width `half` (pixels) at distance `d` (pixels) from its
/// centre line, for a pixel 1 wide.
double band(double d, double half) {
  return std::clamp(std::min(half + 0.5 - d, 2 * half), 0.0, 1.0);
}

void blend(Rgb& pixel, const Rgb& colour, double alpha) {
  pixel.r += (colour.r - pixel.r) * alpha;
  pixel.g += (colour.g - pixel.g) * alpha;
  pixel.b += (colour.b - pixel.b) * alpha;
}

/// Pixels from the pixel centre (u, v in world units) to the nearest line of a grid of the
/// given spacing (world units), shifted by `offset`, along one axis.
double grid_distance(double w, double spacing, double offset, double side) {
  const double t = (w - offset) / spacing;
  return std::abs(t - std::round(t)) * spacing * side;
}

/// Draws tile (x, y) of zoom z.
geolens::Image draw_tile(int z, int tile_x, int tile_y, const std::vector<Town>& towns) {
  const double side = double(kTile) * (1 << z);
  std::vector<Rgb> canvas(size_t(kTile) * kTile);
  for (int j = 0; j < kTile; ++j)
    for (int i = 0; i < kTile; ++i) {
      const double px = tile_x * kTile + i + 0.5, py = tile_y * kTile + j + 0.5;
      const double u = px / side, v = py / side;
      Rgb pixel = kLand;
      // Parks: soft-edged blobs.
      const double park = std::sin(23 * u + 3 * std::sin(7 * v)) * std::sin(19 * v + 2 * u);
      blend(pixel, kPark, std::clamp((park - 0.75) * side / 40, 0.0, 1.0));
      // Roads: streets (zoom >= 4), minor roads (zoom >= 2), motorways; each a white band with a
      // darker casing, of a fixed width on screen.
      struct Level {
        double spacing;
        int from_zoom;
        double half;
        Rgb colour;
      };
      for (const Level& level : {Level{1.0 / 192, 4, 1.0, kRoad}, Level{1.0 / 24, 2, 2.0, kRoad},
                                 Level{1.0 / 3, 0, 3.0, kMotorway}}) {
        if (z < level.from_zoom) continue;
        const double offset = level.spacing * 0.37;
        const double d = std::min(grid_distance(u, level.spacing, offset, side),
                                  grid_distance(v, level.spacing, offset, side));
        blend(pixel, kCasing, band(d, level.half + 0.8));
        blend(pixel, level.colour, band(d, level.half));
      }
      // The river, over the roads (bridges are not drawn), at least 3 pixels wide.
      const double slope = (river(u + 1e-4) - river(u - 1e-4)) / 2e-4;
      const double d_river = std::abs(v - river(u)) / std::sqrt(1 + slope * slope) * side;
      blend(pixel, kWater, band(d_river, std::max(0.004 * side, 1.5)));
      canvas[size_t(j) * kTile + size_t(i)] = pixel;
    }
  // Labels of the towns this zoom shows: a dot and the name, with a halo.
  auto fill = [&](Box box, const Rgb& colour) {
    box = {box.x0 - tile_x * kTile, box.y0 - tile_y * kTile, box.x1 - tile_x * kTile,
           box.y1 - tile_y * kTile};
    const int i0 = std::max(0, int(std::floor(box.x0))),
              i1 = std::min(kTile, int(std::ceil(box.x1)));
    const int j0 = std::max(0, int(std::floor(box.y0))),
              j1 = std::min(kTile, int(std::ceil(box.y1)));
    for (int j = j0; j < j1; ++j)
      for (int i = i0; i < i1; ++i) {
        const double cover = (std::min(box.x1, i + 1.0) - std::max(box.x0, double(i))) *
                             (std::min(box.y1, j + 1.0) - std::max(box.y0, double(j)));
        blend(canvas[size_t(j) * kTile + size_t(i)], colour, std::clamp(cover, 0.0, 1.0));
      }
  };
  const Box tile_box{double(tile_x * kTile), double(tile_y * kTile), double((tile_x + 1) * kTile),
                     double((tile_y + 1) * kTile)};
  for (const Town& town : towns) {
    if (town.rank > z || !overlap(label_box(town, side), tile_box)) continue;
    const double s = text_scale(town.rank), x = town.u * side, y = town.v * side;
    const double left = x + 6, top = y - 3.5 * s;
    for (int pass = 0; pass < 2; ++pass) {
      const double grow = pass == 0 ? 1.0 : 0.0;  // the halo first
      const Rgb& colour = pass == 0 ? kHalo : kInk;
      fill({x - 3 - grow, y - 3 - grow, x + 3 + grow, y + 3 + grow}, colour);
      for (const Box& b : town.strokes)
        fill({left + b.x0 * s - grow, top + b.y0 * s - grow, left + b.x1 * s + grow,
              top + b.y1 * s + grow},
             colour);
    }
  }
  geolens::Image tile(kTile, kTile, 3);
  for (size_t k = 0; k < canvas.size(); ++k) {
    tile.pixels[3 * k] = uint8_t(std::lround(canvas[k].r));
    tile.pixels[3 * k + 1] = uint8_t(std::lround(canvas[k].g));
    tile.pixels[3 * k + 2] = uint8_t(std::lround(canvas[k].b));
  }
  return tile;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: make_xyz_tiles OUTPUT_FOLDER [MAX_ZOOM]\n");
    return 2;
  }
  const int max_zoom = argc == 3 ? std::atoi(argv[2]) : 5;
  if (max_zoom < 0 || max_zoom > 8) {
    std::fprintf(stderr, "make_xyz_tiles: MAX_ZOOM must be in [0, 8], got '%s'\n", argv[2]);
    return 2;
  }
  const std::filesystem::path folder = argv[1];
  const std::vector<Town> towns = make_towns(max_zoom);
  try {
    for (int z = 0; z <= max_zoom; ++z)
      for (int x = 0; x < 1 << z; ++x) {
        const std::filesystem::path column = folder / std::to_string(z) / std::to_string(x);
        std::filesystem::create_directories(column);
        for (int y = 0; y < 1 << z; ++y)
          geolens::save_image((column / (std::to_string(y) + ".png")).string(),
                              draw_tile(z, x, y, towns));
      }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_xyz_tiles: %s\n", e.what());
    return 1;
  }
  std::printf("make_xyz_tiles: wrote zooms 0 to %d of %zu towns to '%s'\n", max_zoom, towns.size(),
              folder.string().c_str());
  return 0;
}
