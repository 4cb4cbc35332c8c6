#include "view_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "habuffer/option_rules.h"
#include "habuffer/pixel_depth.h"
#include "habuffer/technique_descriptor.h"
#include "technique_edit.h"

namespace habuffer::view {
namespace {

constexpr std::size_t kPlotFrames = 120;

// The technique combo: a switch asks for the technique with its other options kept.
void technique_combo(const TechniqueConfig& config, PanelRequest& request) {
  const std::string current = to_string(config.technique);
  if (!ImGui::BeginCombo("technique", current.c_str())) return;
  for (const TechniqueDescriptor* d : technique_registry()) {
    const std::string name(d->name);
    if (ImGui::Selectable(name.c_str(), name == current) && name != current)
      request.config = with_technique(config, *parse_technique(name));
  }
  ImGui::EndCombo();
}

// One text field per option the technique takes, as the CLI spells values;
// Enter applies it (the option's own parser and the configuration's rules).
void option_fields(PanelState& state, const TechniqueConfig& config, PanelRequest& request) {
  for (const TechniqueOption* o : editable_options(config.technique)) {
    const std::string flag(o->flag);
    std::string& text = state.edits[flag];
    if (text.empty()) text = option_text(*o, config);
    char buffer[64] = {};
    text.copy(buffer, sizeof buffer - 1);
    ImGui::SetNextItemWidth(120);
    if (ImGui::InputText(("--" + flag).c_str(), buffer, sizeof buffer, ImGuiInputTextFlags_EnterReturnsTrue)) {
      try {
        request.config = with_option(config, *o, buffer);
        state.refusal.clear();
      } catch (const std::invalid_argument& e) {
        state.refusal = e.what();
      }
      state.edits.clear();  // every field shows the running values again
    } else {
      text = buffer;
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s (%s)", std::string(o->help).c_str(), std::string(o->value_name).c_str());
  }
}

// The HA-buffer's table: automatic (sized from the counting pass, adapted by
// SPEC 8), or fixed at a load factor of the last frame's fragments.
void load_control(PanelState& state, const TechniqueConfig& config, const FrameFigures& figures,
                  PanelRequest& request) {
  if (!uses_table(config.technique)) return;
  bool changed = ImGui::Checkbox("fixed load", &state.fixed_load);
  if (state.fixed_load) {
    ImGui::SameLine();
    ImGui::SetNextItemWidth(140);
    changed = ImGui::SliderFloat("load", &state.load, 0.05f, 1.0f, "%.2f") || changed;
  }
  if (!changed || ImGui::IsItemActive()) return;
  TechniqueConfig c = config;
  c.buffer.table = state.fixed_load
                       ? table_for_load(config.buffer.screen, std::max<std::uint64_t>(figures.counters.stored(), 1),
                                        static_cast<double>(state.load))
                       : Extent{};
  request.config = c;
}

// Shadows on or off, and the light's direction while on.
void shadow_controls(PanelState& state, const ShadowLight* light, PanelRequest& request) {
  bool on = light != nullptr;
  if (ImGui::Checkbox("shadows", &on)) request.shadows = on;
  if (light == nullptr) return;
  // The light buffer is gathered again when a slider is let go, not while it moves.
  ImGui::SetNextItemWidth(140);
  ImGui::SliderFloat("light azimuth", &state.light_azimuth, -180.0f, 180.0f, "%.0f deg");
  bool let_go = ImGui::IsItemDeactivatedAfterEdit();
  ImGui::SetNextItemWidth(140);
  ImGui::SliderFloat("light elevation", &state.light_elevation, 5.0f, 90.0f, "%.0f deg");
  let_go = ImGui::IsItemDeactivatedAfterEdit() || let_go;
  if (let_go) request.light = light_direction(state.light_azimuth, state.light_elevation);
  const LightFigures& l = light->figures();
  ImGui::Text("light %s: table %s, %llu records, %u gathers, %.1f ms", l.size.str().c_str(), l.table.str().c_str(),
              static_cast<unsigned long long>(l.stored), l.attempts, l.build_ms);
}

void figures_table(const FrameFigures& f, const PanelState& state, const TechniqueConfig& config) {
  const Counters& c = f.counters;
  ImGui::Text("fragments %llu  stored %llu", static_cast<unsigned long long>(c.fragments),
              static_cast<unsigned long long>(c.stored()));
  ImGui::Text("load %.3f  capacity %llu", f.load(), static_cast<unsigned long long>(f.capacity));
  if (f.table.area() > 0) ImGui::Text("table %s  max age %u", f.table.str().c_str(), f.max_age);
  if (c.failures() > 0)
    ImGui::TextColored(ImVec4(1, 0.4f, 0.3f, 1), "failures %llu (of them culled %llu)",
                       static_cast<unsigned long long>(c.failures()), static_cast<unsigned long long>(c.culled));
  else
    ImGui::Text("failures 0  culled %llu", static_cast<unsigned long long>(c.culled));
  if (f.too_deep)  // growth stopped: render's rule, said where the user looks
    ImGui::TextWrapped("%s", too_deep_message(*f.too_deep, config.buffer.age_bits).c_str());
  ImGui::Text("memory %.2f MiB  attempts %u", static_cast<double>(f.memory_bytes) / (1024.0 * 1024.0), f.attempts);
  ImGui::Text("GPU ms: clear %.2f count %.2f gather %.2f sort %.2f resolve %.2f", f.clear_ms, f.count_ms, f.gather_ms,
              f.sort_ms, f.resolve_ms);
  if (state.psnr) {
    if (std::isinf(*state.psnr))
      ImGui::Text("PSNR vs exact: inf (equal)");
    else
      ImGui::Text("PSNR vs exact: %.2f dB", *state.psnr);
  } else {
    ImGui::TextDisabled("PSNR vs exact: press P");
  }
  const std::vector<float> plot(state.frame_ms.begin(), state.frame_ms.end());
  ImGui::PlotLines("frame ms", plot.data(), static_cast<int>(plot.size()), 0, nullptr, 0.0f, FLT_MAX, ImVec2(0, 50));
}

}  // namespace

glm::vec3 light_direction(float azimuth_deg, float elevation_deg) {
  const float a = glm::radians(azimuth_deg), e = glm::radians(elevation_deg);
  return {-std::cos(e) * std::sin(a), -std::sin(e), -std::cos(e) * std::cos(a)};
}

void light_angles(glm::vec3 d, float& azimuth_deg, float& elevation_deg) {
  d = glm::normalize(d);
  elevation_deg = glm::degrees(std::asin(std::clamp(-d.y, -1.0f, 1.0f)));
  azimuth_deg = glm::degrees(std::atan2(-d.x, -d.z));
}

PanelRequest draw_panel(PanelState& state, const TechniqueConfig& config, const FrameFigures& figures,
                        const ShadowLight* light, Overlay& overlay) {
  state.frame_ms.push_back(static_cast<float>(figures.frame_ms));
  while (state.frame_ms.size() > kPlotFrames) state.frame_ms.pop_front();
  PanelRequest request;
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowBgAlpha(0.85f);
  // Collapsible by its title bar: collapsed, it covers only that bar.
  const bool open = ImGui::Begin("habuffer", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  if (open) {
    technique_combo(config, request);
    option_fields(state, config, request);
    load_control(state, config, figures, request);
    shadow_controls(state, light, request);
    int o = static_cast<int>(overlay);
    ImGui::Combo("overlay", &o, "none\0depth complexity\0culled\0max age\0light T (shadows)\0");
    overlay = static_cast<Overlay>(o);
    const std::string unshown = overlay_unshown(overlay, config, light);
    if (!unshown.empty()) ImGui::TextColored(ImVec4(1, 0.8f, 0.3f, 1), "%s", unshown.c_str());
    if (ImGui::Button("PSNR vs exact (P)")) request.psnr = true;
    if (!state.refusal.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.3f, 1), "%s", state.refusal.c_str());
    ImGui::Separator();
    figures_table(figures, state, config);
  }
  const float scale = ImGui::GetIO().DisplayFramebufferScale.x;
  state.covers_from = open ? ImGui::GetWindowPos().x * scale : 0.0f;
  state.covers_to = open ? (ImGui::GetWindowPos().x + ImGui::GetWindowSize().x) * scale : 0.0f;
  ImGui::End();
  return request;
}

std::string overlay_unshown(Overlay overlay, const TechniqueConfig& config, const ShadowLight* light) {
  const std::string technique = to_string(config.technique);
  if (overlay == Overlay::Age && !uses_table(config.technique))
    return "max age is the HA-buffer's: technique " + technique + " has no ages to show";
  if (overlay == Overlay::Culled && !uses_table(config.technique))
    return "culled is the HA-buffer's early cull: technique " + technique + " culls nothing";
  if (overlay == Overlay::Culled && config.buffer.early_cull_tau <= 0.0f)
    return "culled shows early cull: it is off (--early-cull-tau)";
  if (overlay == Overlay::Shadow && light == nullptr) return "light T needs shadows on";
  return {};
}

}  // namespace habuffer::view
