/// @file
/// habuffer-view's command line: the scene and camera options of `habuffer
/// render` (scene_options.h), the technique options of every command (the
/// technique option table), the window, and the scripted runs that tests and
/// the README picture use (--frames, --screenshot, --resize, --cycle). One
/// declaration per option (CommandSpec), so the CLI's rules hold here too:
/// declared files checked before any work, unknown or unread options refused.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "cli_args.h"
#include "habuffer/camera.h"
#include "habuffer/lossless_build.h"
#include "habuffer/resize_policy.h"
#include "habuffer/scene_catalog.h"
#include "habuffer/technique.h"

namespace habuffer::view {

/// A heat map drawn over the view (none, or one of these).
enum class Overlay { None, Depth, Culled, Age, Shadow };
/// "none", "depth", "culled", "age", "shadow".
const char* to_string(Overlay o);

/// A scripted window resize: at frame `frame` (counted from 0) the window becomes `size`.
struct ScriptedResize {
  std::uint32_t frame = 0;
  Extent size;
};

/// Everything the command line says (see the file comment).
struct ViewSettings {
  std::string scene;                       ///< a catalog name or a mesh file
  SceneOptions scene_options;              ///< the scene's own options
  std::vector<std::string> opaque_meshes;  ///< mesh indices drawn opaque
  std::optional<float> yaw, pitch;         ///< the scene's defaults where absent
  float fov = 45.0f;
  glm::vec3 background{1.0f};
  Extent window;  ///< the framebuffer's first size
  /// The technique: its options over the buffer's; the table and the pool
  /// automatic unless given (the frame driver sizes and adapts them).
  TechniqueConfig technique;
  OffsetSource offsets;
  ResizePolicy policy;
  bool lossless = false;
  std::uint32_t max_attempts = 1;
  Overlay overlay = Overlay::None;
  bool gui = true;                 ///< the panel (off: the scene alone in the window)
  std::uint32_t frames = 0;        ///< 0: until the window closes
  std::string screenshot;          ///< the last frame's image (the composited scene, no panel)
  std::string window_shot;         ///< the last frame's window, panel included
  std::string report;              ///< the run's JSON report
  std::vector<ScriptedResize> resizes;
  std::uint32_t cycle = 0;         ///< technique switches, one per frame, through every registered technique
  bool psnr = false;               ///< the last frame's PSNR against the exact reference (--psnr)
  bool shadows = false;            ///< translucent shadows from a spot along light_dir
  glm::vec3 light_dir{-0.4f, -1.0f, -0.3f};
  Extent light_size{1024, 1024};   ///< the light map's pixels
};

/// The declaration (usage, options, notes).
const cli::CommandSpec& view_spec();
/// Its help, as `habuffer-view --help` prints it.
std::string view_help();
/// Reads `args` (made from view_spec()); throws cli::UsageError for bad or conflicting values.
ViewSettings parse_view_settings(const cli::Args& args);

}  // namespace habuffer::view
