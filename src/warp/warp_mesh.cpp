#include "geolens/warp/warp_mesh.h"

#include <string>

#include "geolens/core/errors.h"

namespace geolens {

WarpMesh identity_warp(int width, int height) {
  require(width > 0 && height > 0, "identity_warp",
          "size must be positive, got " + std::to_string(width) + " x " + std::to_string(height));
  WarpMesh identity;
  identity.F.resize(2, 3);
  identity.F << 0, 1, 2, 0, 2, 3;
  identity.source.resize(4, 2);
  identity.source << 0, 0, width, 0, width, height, 0, height;
  identity.screen = identity.source;
  identity.screen_width = width;
  identity.screen_height = height;
  return identity;
}

}  // namespace geolens
