#include "panel.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <cstdio>
#include <exception>
#include <iostream>

#include "geolens/lens/geometric_lens.h"
#include "script.h"

namespace geolens::view {

namespace {

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
  ImGui::Checkbox("wireframe (W)", &viewer.wireframe);
  ImGui::SameLine();
  ImGui::Checkbox("outlines", &viewer.outlines);
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
    if (viewer.has_image()) {
      ImGui::Text("%s  %d x %d", viewer.image_path().c_str(), viewer.image().width,
                  viewer.image().height);
      method_controls(viewer);
      ImGui::Separator();
      lens_table(viewer);
      ImGui::Separator();
      ImGui::Text("frame %.1f ms (%.0f fps)   solve %.1f ms", state.frame_ms,
                  state.frame_ms > 0 ? 1000 / state.frame_ms : 0.0, viewer.frame().solve_ms);
      ImGui::Separator();
      const std::string arguments = viewer.lens_arguments();
      ImGui::TextWrapped("%s", arguments.c_str());
      if (ImGui::Button("copy --lens arguments")) ImGui::SetClipboardText(arguments.c_str());
      ImGui::SameLine();
      if (ImGui::Button("print")) std::cout << arguments << std::endl;
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
          "circle; Del: remove the selected; right drag: pan; wheel elsewhere: zoom the view; "
          "F: fit; W: wireframe");
  } catch (const std::exception& e) {
    viewer.message = e.what();
  }
  if (!viewer.message.empty())
    ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "%s", viewer.message.c_str());
  ImGui::End();
  return requests;
}

}  // namespace geolens::view
