/// @file
/// habuffer-view's panel (Dear ImGui): the technique and its options (the
/// technique option table's rows, edited as the CLI spells them), the
/// HA-buffer's load, the overlay, and the live figures of the last frame
/// with a frame-time plot. It only asks: the run applies what it returns.
#pragma once

#include <deque>
#include <map>
#include <optional>
#include <string>

#include "habuffer/technique.h"
#include <glm/vec3.hpp>

#include "oit_session.h"
#include "shadow_light.h"
#include "view_command.h"

namespace habuffer::view {

/// What the panel keeps between frames.
struct PanelState {
  std::map<std::string, std::string> edits;  ///< option flag -> the text being typed
  std::string refusal;                       ///< the library's last refusal, shown until the next change
  std::optional<double> psnr;                ///< the last PSNR measured against the exact reference
  std::deque<float> frame_ms;                ///< recent frame times, for the plot
  bool fixed_load = false;                   ///< the HA-buffer's table fixed at `load` of the last frame's fragments
  float load = 0.6f;
  /// The light's direction as the sliders hold it (degrees): azimuth around
  /// the vertical, elevation below the horizon (light_direction()).
  float light_azimuth = 0.0f, light_elevation = 60.0f;
  /// The columns of the window's framebuffer the panel covered last frame
  /// ([covers_from, covers_to) pixels; empty when collapsed): the scene is
  /// framed in the part it leaves free.
  float covers_from = 0.0f, covers_to = 0.0f;
};

/// The direction the light sliders describe.
glm::vec3 light_direction(float azimuth_deg, float elevation_deg);
/// The sliders' angles of `direction` (any non-zero vector).
void light_angles(glm::vec3 direction, float& azimuth_deg, float& elevation_deg);

/// What the user asked for this frame.
struct PanelRequest {
  std::optional<TechniqueConfig> config;  ///< a new technique or option values
  bool psnr = false;                      ///< measure PSNR against the exact reference
  std::optional<bool> shadows;            ///< shadows switched on or off
  std::optional<glm::vec3> light;         ///< the light turned (shadows on)
};

/// Why `overlay` shows nothing for `config` (`light`: the shadows' light, or
/// nullptr), as the panel says it; empty when it shows something. The
/// command line refuses the same cases for the starting technique.
std::string overlay_unshown(Overlay overlay, const TechniqueConfig& config, const ShadowLight* light);

/// Draws the panel for the running `config` and `figures` (`light`: the
/// shadows' light, or nullptr); `overlay` is edited in place.
PanelRequest draw_panel(PanelState& state, const TechniqueConfig& config, const FrameFigures& figures,
                        const ShadowLight* light, Overlay& overlay);

}  // namespace habuffer::view
