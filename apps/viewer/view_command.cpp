#include "view_command.h"

#include <cmath>

#include "file_values.h"
#include "habuffer/printable.h"
#include "habuffer/render/image.h"
#include "hash_options.h"
#include "scene_options.h"
#include "technique_flags.h"

namespace habuffer::view {

using cli::Args;
using cli::OptionSpec;
using cli::UsageError;

const char* to_string(Overlay o) {
  switch (o) {
    case Overlay::Depth: return "depth";
    case Overlay::Culled: return "culled";
    case Overlay::Age: return "age";
    case Overlay::Shadow: return "shadow";
    case Overlay::None: break;
  }
  return "none";
}

const cli::CommandSpec& view_spec() {
  using cli::reads_in;
  using cli::writes;
  using cli::writes_creating_parents;
  static const cli::CommandSpec spec{
      "--scene NAME|FILE [OPTIONS]",
      std::vector<OptionSpec>{
          {"scene", "NAME|FILE", "",
           "engine, wuson, spider (assimp-testmodels), hairball, quads, planes, or a mesh file",
           reads_in(cli::scene_file, "{}")},
          {"size", "WxH", "960x720", "the window's framebuffer at the start (it follows window resizes)"},
          {"table", "WxH|auto", "auto",
           "the HA-buffer's table; auto sizes the first from a counting pass and adapts between frames (SPEC 8)"},
          {"yaw", "DEG", "", "camera yaw at the start (default: the scene's); drag with the left button"},
          {"pitch", "DEG", "", "camera pitch in [-90, 90] at the start (default: the scene's)"},
          {"fov", "DEG", "45", "vertical field of view in (1, 179); the mouse wheel changes it"},
          {"background", "R,G,B", "1,1,1", "each in [0, 1]"},
          {"opaque-meshes", "I,J,...", "", "meshes (indices in file order) drawn opaque with the depth test"},
          {"overlay", "none|depth|culled|age|shadow", "none",
           "a heat map over the view: fragments, early-culled fragments, max age per pixel (the HA-buffer's), the "
           "light's T at the nearest surface (--shadows)"},
          {"no-gui", "", "", "no panel: the scene alone in the window"},
          {"frames", "N", "0", "frames to render, then exit (0: until the window closes)"},
          {"screenshot", "IMAGE", "",
           "the last frame's composited scene (no panel, no overlay): PNG, or EXR/HDR/TIFF by extension",
           writes_creating_parents()},
          {"window-shot", "IMAGE", "", "the last frame's whole window, panel and overlay included",
           writes_creating_parents()},
          {"report", "REPORT.json", "",
           "the run: every frame's figures, technique switches, resizes, resident memory and live GL objects",
           writes()},
          {"resize", "F:WxH[,...]", "", "scripted window resizes: at frame F the window becomes WxH"},
          {"cycle", "N", "0", "scripted technique switches: one per frame through every technique, N in all"},
          {"psnr", "", "", "the last frame's PSNR against the exact reference (the P key does it live)"},
          {"shadows", "", "",
           "translucent shadows (seed 000, section 6) from a spot along --light-dir, as habuffer render --shadows"},
          {"light-dir", "X,Y,Z", "-0.4,-1,-0.3", "(--shadows) where the light shines; the panel turns it"},
          {"light-size", "WxH", "1024x1024", "(--shadows) the light map's pixels (the light buffer's screen)"}} +
          cli::scene_option_specs() + cli::shared_options({"technique"}) + cli::technique_option_specs(false) +
          cli::technique_option_specs(true) + cli::shared_options({"layout", "offsets", "seed", "lossless", "max-attempts"}),
      "  Keys: left drag orbits, wheel zooms, P measures PSNR against the exact reference, O cycles the overlay,\n"
      "  T the technique, G hides the panel, Esc quits.\n"
      "  Exit codes: 0 ok, 1 bad data (scene, GL limits, no window) or a scripted step refused, 2 bad usage.\n"};
  return spec;
}

std::string view_help() {
  // CommandSpec::help() names the CLI ("usage: habuffer "): this is its own executable.
  std::string h = view_spec().help();
  const std::string cli_prefix = "usage: habuffer ";
  if (h.rfind(cli_prefix, 0) == 0) h.replace(0, cli_prefix.size(), "usage: habuffer-view ");
  return h;
}

namespace {

Overlay parse_overlay(const std::string& text) {
  for (Overlay o : {Overlay::None, Overlay::Depth, Overlay::Culled, Overlay::Age, Overlay::Shadow})
    if (text == to_string(o)) return o;
  throw UsageError("option --overlay: " + excerpt(text) + " is not none, depth, culled, age or shadow");
}

// "F:WxH,..." in order of F, each size with pixels.
std::vector<ScriptedResize> parse_resizes(const Args& args) {
  std::vector<ScriptedResize> out;
  if (!args.has("resize")) return out;
  for (const std::string& item : args.list("resize", "")) {
    const auto colon = item.find(':');
    ScriptedResize r;
    const auto bad = [&] {
      return UsageError("option --resize: " + excerpt(item) + " is not FRAME:WxH (a frame number and a size)");
    };
    if (colon == std::string::npos) throw bad();
    try {
      std::size_t used = 0;
      const unsigned long f = std::stoul(item.substr(0, colon), &used);
      if (used != colon || f > 1000000) throw bad();
      r.frame = static_cast<std::uint32_t>(f);
      const std::optional<Extent> size = parse_extent(std::string_view(item).substr(colon + 1));
      if (!size) throw bad();
      r.size = *size;
    } catch (const std::exception&) {
      throw bad();
    }
    if (r.size.area() == 0) throw bad();
    if (!out.empty() && r.frame <= out.back().frame)
      throw UsageError("option --resize: frames must increase (" + std::to_string(r.frame) + " after " +
                       std::to_string(out.back().frame) + ")");
    out.push_back(r);
  }
  return out;
}

}  // namespace

ViewSettings parse_view_settings(const Args& args) {
  ViewSettings s;
  s.scene = args.required("scene");
  cli::check_camera_args(args);
  cli::refuse_scene_options_that_do_not_apply(args);
  s.scene_options = cli::parse_scene_options(args);
  if (args.has("opaque-meshes")) s.opaque_meshes = args.list("opaque-meshes", "");
  if (args.has("yaw")) s.yaw = static_cast<float>(args.real("yaw", 0.0));
  if (args.has("pitch")) s.pitch = static_cast<float>(args.real("pitch", 0.0));
  s.fov = static_cast<float>(args.real("fov"));
  s.background = cli::parse_background(args.str("background"));
  s.window = args.size("size");
  if (s.window.area() == 0) throw UsageError("option --size: " + s.window.str() + " has no pixels");

  static_cast<TechniqueChoice&>(s.technique) = cli::parse_technique_options(args);
  const std::string table = args.str("table");
  s.technique.buffer = cli::parse_buffer_config(args, s.window, table == "auto" ? Extent{} : args.extent("table").value());
  cli::refuse_samples_without_lists(s.technique.buffer, s.technique.technique);
  s.offsets = cli::parse_offset_source(args, s.technique.buffer);
  s.lossless = args.has("lossless");
  s.max_attempts = args.u32_in("max-attempts", 1, 1000);
  args.refuse_unless(s.lossless, {"max-attempts"}, "without --lossless");

  s.overlay = parse_overlay(args.str("overlay"));
  s.gui = !args.has("no-gui");
  s.frames = args.u32_in("frames", 0, 10000000);
  s.screenshot = args.str("screenshot");
  s.window_shot = args.str("window-shot");
  for (const char* image : {"screenshot", "window-shot"})
    if (args.has(image)) cli::usage_errors(image, [&] { check_image_extension(args.required(image)); });
  const bool scripted_end = s.frames > 0;
  args.refuse_unless(scripted_end, {"screenshot", "window-shot", "report", "psnr"},
                     "without --frames N (they describe the last frame of a scripted run)");
  s.report = args.str("report");
  s.resizes = parse_resizes(args);
  s.cycle = args.u32_in("cycle", 0, 1000000);
  // A scripted step beyond the last frame would be ignored: refused instead.
  if (s.frames > 0 && s.cycle > s.frames - 1)
    throw UsageError("option --cycle: " + std::to_string(s.cycle) + " switches need " + std::to_string(s.cycle + 1) +
                     " frames (one a frame after the first), not --frames " + std::to_string(s.frames));
  if (s.frames > 0 && !s.resizes.empty() && s.resizes.back().frame >= s.frames)
    throw UsageError("option --resize: frame " + std::to_string(s.resizes.back().frame) + " is beyond --frames " +
                     std::to_string(s.frames));
  s.psnr = args.has("psnr");
  s.shadows = args.has("shadows");
  // render's heat-map rule: ages and early cull are the HA-buffer's.
  if ((s.overlay == Overlay::Age || s.overlay == Overlay::Culled) && !uses_table(s.technique.technique))
    throw UsageError("option --overlay " + args.str("overlay") + ": the HA-buffer's (ages, early cull), not technique " +
                     to_string(s.technique.technique) + "'s");
  if (s.overlay == Overlay::Shadow && !s.shadows)
    throw UsageError("option --overlay shadow: the light's transmittance needs --shadows");
  args.refuse_unless(s.shadows, {"light-dir", "light-size"}, "without --shadows");
  s.light_dir = cli::parse_point("light-dir", args.str("light-dir"));
  if (s.light_dir == glm::vec3(0.0f)) throw UsageError("option --light-dir: the zero vector has no direction");
  s.light_size = args.size("light-size");
  if (s.light_size.area() == 0) throw UsageError("option --light-size: " + s.light_size.str() + " has no pixels");
  if (s.shadows && s.technique.buffer.samples > 1)
    throw UsageError("option --samples: translucent shadows are drawn with one sample a pixel; use --samples 1");
  if (s.shadows && s.technique.buffer.layout == Layout::L32)
    throw UsageError("option --shadows needs --layout 64 (the view's shaders read the light's 64-bit records)");
  return s;
}

}  // namespace habuffer::view
