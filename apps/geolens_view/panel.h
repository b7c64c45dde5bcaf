#pragma once
// The ImGui panel: the method and its options, the overlays, each lens with its measured zoom
// and flips, the frame and solve times, the lenses as --lens arguments, a screenshot.

#include <optional>
#include <string>

#include "viewer.h"

namespace geolens::view {

/// What the panel keeps between frames: the text fields, the frame time.
struct PanelState {
  std::string open_path;
  std::string screenshot_path = "geolens-view.png";
  std::string export_path = "geolens-view-lenses.txt";
  double frame_ms = 0;  ///< smoothed time between frames, milliseconds
};

/// What the user asked of the frame loop.
struct PanelRequests {
  std::optional<std::string> screenshot;  ///< a path already checked (not the input image)
};

/// Draws the panel (inside an ImGui frame) and applies what is changed in it to `viewer`.
PanelRequests draw_panel(Viewer& viewer, PanelState& state);

/// Draws over the picture, behind every ImGui window, panel or not: with outlines on, the polygon
/// lenses' outlines (Viewer::region_outlines); the outline of the polygon being drawn (its edges,
/// the edge on to the pointer, a dot at each vertex); and while split each half's method.
void draw_overlays(Viewer& viewer);

}  // namespace geolens::view
