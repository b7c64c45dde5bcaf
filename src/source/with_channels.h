#pragma once
// Private: per-texel loops compiled for each channel count (the mip pyramid, the renderer).

#include <type_traits>

namespace geolens {

/// Calls f(std::integral_constant<int, channels>{}) for channels in [1, 4] (4 for any other
/// value), so that a loop over texels is compiled for each channel count.
template <class F>
void with_channels(int channels, F&& f) {
  switch (channels) {
    case 1:
      f(std::integral_constant<int, 1>{});
      break;
    case 2:
      f(std::integral_constant<int, 2>{});
      break;
    case 3:
      f(std::integral_constant<int, 3>{});
      break;
    default:
      f(std::integral_constant<int, 4>{});
      break;
  }
}

}  // namespace geolens
