#include "panel.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <cstdio>
#include <exception>
#include <iostream>

#include "geolens/lens/geometric_lens.h"
#include "geolens/render/annotate.h"
#include "script.h"

namespace geolens::view {

namespace {

ImU32 colour_of(const std::array<uint8_t, 3>& c) { return IM_COL32(c[0], c[1], c[2], 255); }

// The heatmap's scale (heat_colour from 0 to the maximum, and the flipped colour) and its maximum.
void heat_legend(Viewer& viewer) {
  const float width = 230, height = 12;
  const ImVec2 at = ImGui::GetCursorScreenPos();
  ImDrawList& list = *ImGui::GetWindowDrawList();
  constexpr int kSteps = 46;
  for (int i = 0; i < kSteps; ++i)
    list.AddRectFilled(ImVec2(at.x + width * float(i) / kSteps, at.y),
                       ImVec2(at.x + width * float(i + 1) / kSteps, at.y + height),
                       colour_of(heat_colour((i + 0.5) / kSteps)));
  list.AddRectFilled(ImVec2(at.x + width + 8, at.y),
                     ImVec2(at.x + width + 8 + height, at.y + height), colour_of(kFlippedColour));
  list.AddRect(ImVec2(at.x + width + 8, at.y), ImVec2(at.x + width + 8 + height, at.y + height),
               IM_COL32(200, 200, 200, 255));
  ImGui::Dummy(ImVec2(width + 8 + height, height));
  ImGui::Text("s1/s2 - 1: 0 .. %.2f; black: flipped", viewer.heat_max());
  float heat_max = float(viewer.heat_max());
  if (ImGui::DragFloat("heat max", &heat_max, 0.01f, 0.0f, 100.0f, "%.2f"))
    viewer.set_heat_max(heat_max);
  ImGui::SameLine();
  if (ImGui::Button("auto")) viewer.set_heat_max(0);
}

// The stages of the frame's solve, as the library timed them; a classic lens has none.
void stage_times(const SolvedFrame& frame, const std::string& method) {
  if (const std::optional<StageTimings>& t = frame.stages)
    ImGui::TextWrapped(
        "stages (%d solve%s): lift %.1f, texture %.1f, factorize %.1f, iterate %.1f; total %.1f ms",
        frame.solves, frame.solves == 1 ? "" : "s", t->lift, t->texture, t->factorize, t->iterate,
        t->total);
  else if (method != "geometric")
    ImGui::TextDisabled("stages: none (%s is one step)", method.c_str());
}

void method_controls(Viewer& viewer) {
  if (ImGui::BeginCombo("method", viewer.method().c_str())) {
    for (const std::string& name : method_names())
      if (ImGui::Selectable(name.c_str(), name == viewer.method())) viewer.set_method(name);
    ImGui::EndCombo();
  }
  if (viewer.method() == "geometric") {
    const std::string model = to_string(viewer.options().model);
    if (ImGui::BeginCombo("model", model.c_str())) {
      for (LensModel m : {LensModel::kFocus, LensModel::kLift, LensModel::kField, LensModel::kAuto})
        if (ImGui::Selectable(to_string(m).c_str(), m == viewer.options().model))
          viewer.set_model(m);
      ImGui::EndCombo();
    }
  }
  // Applied when the slider is let go: every value in between would restart the solver.
  int mesh = viewer.options().mesh;
  ImGui::SliderInt("mesh", &mesh, 20, 300);
  if (ImGui::IsItemDeactivatedAfterEdit()) viewer.set_mesh(mesh);
  // Split view: the other method on the right half.
  bool split = !viewer.split().empty();
  if (ImGui::Checkbox("split with", &split))
    viewer.set_split(split ? method_names()[1] : "");  // the first classic lens
  ImGui::SameLine();
  ImGui::SetNextItemWidth(150);
  if (ImGui::BeginCombo("##split", split ? viewer.split().c_str() : "-")) {
    for (const std::string& name : method_names())
      if (ImGui::Selectable(name.c_str(), name == viewer.split())) viewer.set_split(name);
    ImGui::EndCombo();
  }
  ImGui::Checkbox("wireframe (W)", &viewer.wireframe);
  ImGui::SameLine();
  ImGui::Checkbox("heatmap (H)", &viewer.heatmap);
  ImGui::SameLine();
  ImGui::Checkbox("outlines", &viewer.outlines);
  if (viewer.has_detail()) {
    ImGui::SameLine();
    ImGui::Checkbox("detail", &viewer.detail);
  }
  if (viewer.heatmap) heat_legend(viewer);
}

void lens_table(Viewer& viewer) {
  const FrameMeasures& m = viewer.measures();
  ImGui::Text("lenses: %zu; shown: %d flipped, distortion %.2f", viewer.lenses().size(), m.flipped,
              m.conformal_mean);
  // The zoom asked for, the zoom the method built (a focus lens that does not fit where it is
  // is built at the largest zoom that does), the zoom measured at its peak, its flips; the last
  // three belong to the frame on screen, which may lag the lenses by a solve.
  if (ImGui::BeginTable("lenses", 6, ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg)) {
    for (const char* column : {"#", "kind", "zoom", "built", "measured", "flips"})
      ImGui::TableSetupColumn(column);
    ImGui::TableHeadersRow();
    const Magnification* shown = viewer.frame().result.get();
    for (size_t i = 0; i < viewer.lenses().size(); ++i) {
      const Lens& lens = viewer.lenses()[i];
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      const std::string label = std::to_string(i + 1);
      if (ImGui::Selectable(label.c_str(), viewer.selected() == i,
                            ImGuiSelectableFlags_SpanAllColumns))
        viewer.select(i);
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(lens.region.kind().c_str());
      ImGui::TableNextColumn();
      ImGui::Text("%.2f", lens.zoom);
      ImGui::TableNextColumn();
      if (shown && i < shown->zoom_parameter.size()) ImGui::Text("%.2f", shown->zoom_parameter[i]);
      ImGui::TableNextColumn();
      if (i < m.zoom_measured.size()) ImGui::Text("%.2f", m.zoom_measured[i]);
      ImGui::TableNextColumn();
      if (i < m.flips.size()) ImGui::Text("%d", m.flips[i]);
    }
    ImGui::EndTable();
  }
  // Why a lens is built at less than it asks, as the CLI's warning says it.
  const std::vector<std::string>& reasons = viewer.frame().fit_reasons;
  for (size_t i = 0; i < reasons.size(); ++i)
    if (!reasons[i].empty())
      ImGui::TextWrapped("lens %zu: limited by %s", i + 1, reasons[i].c_str());
  if (const std::optional<size_t> s = viewer.selected(); s && *s < viewer.lenses().size()) {
    float zoom = float(viewer.lenses()[*s].zoom);
    if (ImGui::SliderFloat("zoom", &zoom, 1.0f, 8.0f, "%.2f")) viewer.set_zoom(*s, zoom);
    float radius = float(viewer.lenses()[*s].region.size());
    if (ImGui::SliderFloat("radius", &radius, 2.0f,
                           float(std::max(viewer.image().width, viewer.image().height)) / 2,
                           "%.1f"))
      viewer.set_radius(*s, radius);
    if (ImGui::Button("remove (Del)")) viewer.delete_selected();
  }
  if (viewer.drawing_polygon()) {
    ImGui::Text("drawing a polygon: %zu vertices", viewer.polygon_vertices());
    ImGui::SameLine();
    if (ImGui::Button("cancel (Esc)")) viewer.cancel_polygon();
  } else if (ImGui::Button("draw a polygon (P)")) {
    viewer.start_polygon();
  }
}

}  // namespace

PanelRequests draw_panel(Viewer& viewer, PanelState& state) {
  PanelRequests requests;
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(350, 0), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowBgAlpha(0.85f);
  if (!ImGui::Begin("geolens-view")) {
    ImGui::End();
    return requests;
  }
  try {
    ImGui::SetNextItemWidth(230);
    ImGui::InputText("##open", &state.open_path);
    ImGui::SameLine();
    if (ImGui::Button("open image")) viewer.try_open(state.open_path);
    // A file being opened or a view being rendered, off the UI thread: the current image stays.
    if (const std::string status = viewer.status(); !status.empty())
      ImGui::TextUnformatted(status.c_str());
    if (viewer.has_image()) {
      ImGui::Text("%s  %d x %d", viewer.image_path().c_str(), viewer.image().width,
                  viewer.image().height);
      method_controls(viewer);
      ImGui::Separator();
      lens_table(viewer);
      ImGui::Separator();
      ImGui::Text("frame %.1f ms (%.0f fps)   solve %.1f ms", state.frame_ms,
                  state.frame_ms > 0 ? 1000 / state.frame_ms : 0.0, viewer.frame().solve_ms);
      stage_times(viewer.frame(), viewer.method());
      if (!viewer.split().empty()) {
        ImGui::Text("%s: solve %.1f ms", viewer.split().c_str(), viewer.split_frame().solve_ms);
        stage_times(viewer.split_frame(), viewer.split());
      }
      ImGui::Separator();
      const std::string arguments = viewer.lens_arguments();
      ImGui::TextWrapped("%s", arguments.c_str());
      if (ImGui::Button("copy --lens arguments")) ImGui::SetClipboardText(arguments.c_str());
      ImGui::SameLine();
      if (ImGui::Button("print")) std::cout << arguments << std::endl;
      ImGui::SetNextItemWidth(190);
      ImGui::InputText("##export", &state.export_path);
      ImGui::SameLine();
      if (ImGui::Button("export lenses")) {
        viewer.export_lenses(state.export_path);
        viewer.message = "saved " + state.export_path;
      }
      ImGui::SetNextItemWidth(190);
      ImGui::InputText("##shot", &state.screenshot_path);
      ImGui::SameLine();
      if (ImGui::Button("save screenshot")) {
        check_screenshot_path(state.screenshot_path, viewer.image_path(), "screenshot");
        requests.screenshot = state.screenshot_path;
      }
    }
    if (ImGui::CollapsingHeader("mouse and keys"))
      ImGui::TextWrapped(
          "drag a lens: move it; wheel on a lens: zoom; shift+wheel: radius; ctrl+click: add a "
          "circle; P: draw a polygon (click the vertices, double-click to close, Esc cancels); "
          "Del: remove the selected; right drag: pan; wheel elsewhere: zoom the view; F: fit; "
          "W: wireframe; H: heatmap");
  } catch (const std::exception& e) {
    viewer.message = e.what();
  }
  if (!viewer.message.empty())
    ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "%s", viewer.message.c_str());
  ImGui::End();
  return requests;
}

void draw_overlays(Viewer& viewer) {
  ImDrawList& list = *ImGui::GetBackgroundDrawList();
  if (!viewer.split().empty()) {
    const float w = float(viewer.pane_width());
    const ImVec2 top(w, 0), bottom(w, ImGui::GetIO().DisplaySize.y);
    list.AddLine(top, bottom, IM_COL32(20, 20, 22, 255), 3.0f);
    for (int pane = 0; pane < 2; ++pane) {
      const std::string state = viewer.pane_state(pane);
      const std::string name = (pane == 0 ? viewer.method() : viewer.split()) +
                               (state.empty() ? "" : " (" + state + ")");
      const ImVec2 at(float(pane) * w + w - 8 - ImGui::CalcTextSize(name.c_str()).x, 6);
      list.AddRectFilled(ImVec2(at.x - 4, at.y - 2),
                         ImVec2(at.x + ImGui::CalcTextSize(name.c_str()).x + 4, at.y + 16),
                         IM_COL32(0, 0, 0, 150));
      list.AddText(at, IM_COL32(255, 255, 255, 255), name.c_str());
    }
  }
  // The polygon lenses, drawn as the renderer draws circles: white over a dark halo, the
  // selected one orange.
  if (viewer.outlines) {
    for (int pane = 0; pane < (viewer.split().empty() ? 1 : 2); ++pane) {
      for (const Viewer::Outline& o : viewer.region_outlines(pane)) {
        std::vector<ImVec2> points;
        for (const Eigen::Vector2d& p : o.points) points.emplace_back(float(p.x()), float(p.y()));
        const ImU32 ring = o.selected ? IM_COL32(255, 140, 26, 255) : IM_COL32(255, 255, 255, 255);
        list.AddPolyline(points.data(), int(points.size()), IM_COL32(0, 0, 0, 110),
                         ImDrawFlags_Closed, 4.0f);
        list.AddPolyline(points.data(), int(points.size()), ring, ImDrawFlags_Closed, 2.0f);
      }
    }
  }
  const std::vector<Eigen::Vector2d> outline = viewer.polygon_outline();
  if (outline.empty()) return;
  std::vector<ImVec2> points;
  for (const Eigen::Vector2d& p : outline) points.emplace_back(float(p.x()), float(p.y()));
  const ImU32 line = IM_COL32(255, 140, 26, 255), halo = IM_COL32(0, 0, 0, 110);
  list.AddPolyline(points.data(), int(points.size()), halo, ImDrawFlags_None, 4.0f);
  list.AddPolyline(points.data(), int(points.size()), line, ImDrawFlags_None, 2.0f);
  for (size_t i = 0; i + 1 < points.size(); ++i) list.AddCircleFilled(points[i], 3.5f, line);
}

}  // namespace geolens::view
