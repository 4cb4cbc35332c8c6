// habuffer render: a real scene (or a recorded stream) through the HA-buffer,
// headless: the image, its stats, heat maps and the exact reference.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>

#include "commands.h"
#include "file_values.h"
#include "habuffer/gl/egl_context.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/interchange.h"
#include "habuffer/json_writer.h"
#include "habuffer/option_rules.h"
#include "habuffer/render/heatmap.h"
#include "habuffer/render/render_job.h"
#include "habuffer/render/shadow_accuracy.h"
#include "habuffer/transmittance_reference.h"
#include "habuffer/light_view.h"
#include "habuffer/scene_catalog.h"
#include "habuffer/technique_descriptor.h"
#include "habuffer/file_roles.h"
#include "habuffer/printable.h"
#include "habuffer/progress.h"
#include "hash_options.h"
#include "loss_report.h"
#include "render_report.h"
#include "scene_options.h"
#include "technique_flags.h"
#include "vulkan_path.h"

namespace habuffer::cli {
namespace {
constexpr const char* kRenderPaths = kHasVulkanPath ? "gl|cpu|vk" : "gl|cpu";
}  // namespace

const CommandSpec& render_spec() {
  static const CommandSpec spec{
      "render (--scene NAME|FILE | --fragments FRAGS.csv) --out IMAGE [--stats STATS.json] [OPTIONS]",
      std::vector<OptionSpec>{
          {"scene", "NAME|FILE", "",
           "engine, wuson, spider (assimp-testmodels), hairball, quads, planes, or a mesh file", reads_in(scene_file, "{}")},
          {"fragments", "FRAGS.csv", "", "a recorded fragment stream instead of a scene (CPU path)", reads()},
          {"out", "IMAGE", "", "the image: PNG, or EXR/HDR/TIFF (float) by extension", writes_creating_parents()},
          {"stats", "STATS.json", "", "counters, sizes, times per frame", writes()},
          {"size", "WxH", "1024x1024", "the image (harness commands default to 256x256: many runs)"},
          {"path", kRenderPaths, "gl",
           "where the technique runs: gl; cpu or vk (GL rasterizes and captures, the CPU or a Vulkan device builds "
           "and composites); --fragments renders on cpu"},
          {"table", "WxH|auto", "auto",
           "the HA-buffer's table; auto sizes the first from a counting pass, grows it at once when a frame fails "
           "and adapts between frames (SPEC 8)"},
          {"frames", "N", "1", "frames rendered (kept containers between them)"},
          {"yaw", "DEG", "", "camera yaw (default: the scene's)"},
          {"pitch", "DEG", "", "camera pitch in [-90, 90] (default: the scene's)"},
          {"fov", "DEG", "45", "vertical field of view in (1, 179)"},
          {"background", "R,G,B", "1,1,1", "each in [0, 1]"},
          {"heatmap", "depth|age|culled|shadow:IMAGE[,...]", "",
           "heat maps: fragments, max age, culled per pixel, the light's T at the nearest surface (--shadows)", writes_in(heatmap_files, "depth:{}", true)},
          {"reference", "IMAGE", "", "the exact reference; the stats then give psnr, rmse and max_error", writes_creating_parents()},
          {"error", "", "", "psnr, rmse and max_error against the reference without writing it"},
          {"opaque-meshes", "I,J,...", "",
           "meshes (indices in file order) drawn opaque with the depth test; transparent fragments behind them are "
           "rejected before insertion and counted"},
          {"quiet", "", "", "no summary and no progress bar (shown on a terminal for --frames above 1)"},
          {"slot-writes", "", "",
           "(--path gl) the stats' slot_writes, tallied by one more atomic per insert call (compiled in only then; "
           "null otherwise)"},
          {"shadows", "", "",
           "translucent shadows (seed 000, section 6): an HA-buffer of every mesh from the light (opaque ones at "
           "opacity 1), built once, and each fragment's lit colour times the light's transmittance T"},
          {"light-dir", "X,Y,Z", "-0.4,-1,-0.3",
           "(--shadows) where the light shines: a spot placed along it outside the scene, or with --light-ortho a "
           "directional light"},
          {"light-ortho", "", "", "(--shadows) a directional light: an orthographic frustum along --light-dir"},
          {"light-pos", "X,Y,Z", "", "(--shadows) a spot at this point (outside the scene) looking at its centre"},
          {"light-fov", "DEG", "60", "(--shadows) a spot's widest cone in (1, 179); narrowed to the scene"},
          {"light-size", "WxH", "1024x1024", "(--shadows) the light map's pixels (the light buffer's screen)"},
          {"light-table", "WxH|auto", "auto",
           "(--shadows) the light buffer's table; auto sizes it from the light's counting pass and grows it until "
           "nothing is dropped"},
          {"light-cull", "TAU", "0", "(--shadows) the light buffer's early cull, in [0, 1] (0: off; T errs by at most "
                                     "1 - TAU)"},
          {"shadow-error", "N", "",
           "(--shadows) T against the ray-traced reference at up to N receiving points (0: all): the stats' "
           "light.reference"},
          {"shadow-filter", "nearest|pcf", "nearest",
           "(--shadows) T of the nearest light pixel, or pcf: of the four nearest, bilinearly weighted (the bias "
           "doubles)"},
          {"shadow-slope", "S", "2",
           "(--shadows) the bias rule: surfaces up to atan(S) from facing the light never shadow themselves; S "
           "below the light map's short side in pixels (half that with pcf)"}} +
          scene_option_specs() +
          shared_options({"technique"}) + technique_option_specs(false) + technique_option_specs(true) +
          shared_options({"layout", "offsets", "seed", "lossless", "max-attempts", "threads", "insert-order"}),
      "  Exit codes: 0 ok (lost fragments are warned about on stderr), 1 bad data (scene, file, GL limits) or a\n"
      "  --lossless render that still lost fragments, 2 bad usage.\n"};
  return spec;
}

namespace {

// The light of --shadows, before the scene is known (a spot along a
// direction is placed from the scene's bounds: light_for).
struct LightArgs {
  ShadowSettings settings;
  bool spot_along = false;  // --light-dir without --light-ortho
  std::uint64_t error_receivers = 0;  // --shadow-error N (with settings.read_back)
};

std::optional<LightArgs> parse_light(const Args& args) {
  const bool on = args.has("shadows");
  args.refuse_unless(on, {"light-dir", "light-ortho", "light-pos", "light-fov", "light-size", "light-table",
                          "light-cull", "shadow-slope", "shadow-error", "shadow-filter"},
                     "without --shadows");
  if (!on) return std::nullopt;
  args.refuse_unless(!args.has("fragments"), {"shadows"}, "with --fragments (a stream has no world positions)");
  args.refuse_unless(!args.has("light-pos"), {"light-dir", "light-ortho"}, "with --light-pos (a spot looks at the scene)");
  LightArgs l;
  ShadowSettings& s = l.settings;
  s.light.size = args.size("light-size");
  if (s.light.size.area() == 0) throw UsageError("option --light-size: " + s.light.size.str() + " has no pixels");
  const double fov = args.real("light-fov");
  if (!(fov > 1.0 && fov < 179.0)) throw UsageError("option --light-fov: must be in (1, 179) degrees");
  s.light.fov = static_cast<float>(fov);
  if (args.has("light-pos")) {
    s.light.orthographic = false;
    s.light.position = parse_point("light-pos", args.str("light-pos"));
  } else {
    s.light.direction = parse_point("light-dir", args.str("light-dir"));
    // Any other finite vector has a direction, however long or short (frame_light normalises it safely).
    if (s.light.direction == glm::vec3(0.0f)) throw UsageError("option --light-dir: the zero vector has no direction");
    s.light.orthographic = args.has("light-ortho");
    l.spot_along = !s.light.orthographic;
  }
  s.table = args.str("light-table") == "auto" ? Extent{} : args.extent("light-table").value();
  // 0 is off; anything else early cull's threshold by its rule (a float32 in (0, 1], no subnormal).
  s.early_cull_tau = args.real("light-cull") == 0.0
                         ? 0.0f
                         : usage_errors("light-cull", [&] { return parse_cull_threshold(args.str("light-cull")); });
  const double slope = args.real("shadow-slope");
  s.max_slope = static_cast<float>(slope);
  if (!(std::isfinite(s.max_slope) && slope >= 0.0))
    throw UsageError("option --shadow-slope: must be a slope >= 0 that float32 holds");
  args.refuse_unless(!args.has("light-ortho"), {"light-fov"}, "with --light-ortho (a directional light has no cone)");
  const std::string filter = args.str("shadow-filter");
  if (filter != "nearest" && filter != "pcf")
    throw UsageError("option --shadow-filter: '" + filter + "' is not nearest or pcf");
  s.filter = filter == "pcf" ? ShadowFilter::Pcf : ShadowFilter::Nearest;
  usage_errors("", [&] { s.validate(); });  // its messages name their options
  s.read_back = args.has("shadow-error");
  if (s.read_back) l.error_receivers = args.u64_in("shadow-error");
  return l;
}

struct HeatmapRequest {
  std::string kind, path;
};

std::vector<HeatmapRequest> parse_heatmaps(const Args& args, Technique technique) {
  std::vector<HeatmapRequest> out;
  if (!args.has("heatmap")) return out;
  for (const std::string& item : args.list("heatmap", "")) {
    const auto colon = item.find(':');
    const std::string kind = item.substr(0, colon);
    if (colon == std::string::npos || colon + 1 == item.size() ||
        (kind != "depth" && kind != "age" && kind != "culled" && kind != "shadow"))
      throw UsageError("option --heatmap: " + excerpt(item) +
                       " is not depth:IMAGE, age:IMAGE, culled:IMAGE or shadow:IMAGE");
    if (kind == "shadow" && !args.has("shadows"))
      throw UsageError("option --heatmap shadow: the light's transmittance needs --shadows");
    if ((kind == "age" || kind == "culled") && !uses_table(technique))
      throw UsageError("option --heatmap " + kind + ": the HA-buffer's (ages, early cull), not technique " +
                       to_string(technique) + "'s");
    out.push_back({kind, item.substr(colon + 1)});
  }
  return out;
}

// Images need OpenImageIO (the files themselves are checked by their declared
// roles), and an extension it writes: "--out x.txt" is refused before any work.
void check_image_outputs(const Args& args, const std::vector<HeatmapRequest>& heatmaps) {
  if (!has_image_support())
    for (const char* image : {"out", "reference", "heatmap"})
      if (args.has(image))
        throw UsageError(std::string("option --") + image + ": this habuffer was built without image files (" +
                         image_support() + "); give --stats only");
  for (const char* image : {"out", "reference"})
    if (args.has(image)) usage_errors(image, [&] { check_image_extension(args.required(image)); });
  for (const HeatmapRequest& h : heatmaps) usage_errors("heatmap " + h.kind, [&] { check_image_extension(h.path); });
}

RenderSettings parse_settings(const Args& args) {
  RenderSettings s;
  const Extent size = args.size("size");
  if (size.area() == 0) throw UsageError("option --size: " + size.str() + " has no pixels");
  static_cast<TechniqueChoice&>(s) = parse_technique_options(args);
  const std::string table = args.str("table");
  const Extent t = table == "auto" ? Extent{0, 0} : args.extent("table").value();
  s.config = parse_buffer_config(args, size, t);
  refuse_samples_without_lists(s.config, s.technique);
  if (s.config.samples > 1 && args.has("shadows"))
    throw UsageError("option --samples: translucent shadows are not drawn on a multisampled screen; render them "
                     "with --samples 1");
  s.offsets = parse_offset_source(args, s.config);
  const std::string path = args.choice("path");  // the alternatives declared above
  s.path = path == "gl" ? RenderPath::Gl : path == "vk" ? RenderPath::Vk : RenderPath::Cpu;
  s.lossless = args.has("lossless");
  if (!s.lossless && args.has("max-attempts") && !automatic_size(s))
    throw UsageError("option --max-attempts needs --lossless or an automatic size (--table auto, --pool auto)");
  s.max_attempts = args.u32_in("max-attempts", 1, 1000);
  s.frames = args.u32_in("frames", 1, 100000);
  s.threads = args.u32_in("threads", 0, kMaxThreads);
  s.insert_order = insert_order_option(args);
  args.refuse_unless(s.path == RenderPath::Cpu || args.has("fragments"), {"threads", "insert-order"},
                     "with --path " + path + " (the GPU inserts and composites)");
  args.refuse_unless(descriptor(s.technique).takes("insert-order"), {"insert-order"},
                     "with --technique " + to_string(s.technique) + " (it applies to " +
                         techniques_taking("insert-order") + ")");
  args.refuse_unless(s.path == RenderPath::Gl && !args.has("fragments"), {"slot-writes"},
                     "on the CPU path (the GPU path's tally)");
  s.background = parse_background(args.str("background"));
  return s;
}


// --shadow-error: the light buffer's T at every receiving point of the view against the ray-traced reference.
ShadowAccuracy shadow_error(const Scene& scene, const RenderSettings& s, const RenderResult& r, std::uint64_t receivers) {
  const TransmittanceReference reference(scene);
  const ShadowReceivers at{&r.camera, s.config.screen, r.fragments, r.opaque_depth};
  return measure_shadow_accuracy(reference, r.light->view, *r.light_buffer,
                                 RecordLayout(Layout::L64, s.shadows->age_bits), r.light->bias_codes, at, receivers,
                                 s.shadows->filter == ShadowFilter::Pcf);
}

RenderResult render_with_gl(const Args& args, const std::vector<std::string>& opaque_meshes,
                            const std::optional<LightArgs>& light, RenderSettings& s, SceneDescription& described,
                            std::optional<ShadowAccuracy>& accuracy) {
  const SceneOptions options = parse_scene_options(args);
  Scene scene = make_scene(args.required("scene"), options);
  make_opaque(opaque_meshes, scene);
  if (light) {
    s.shadows = light->settings;
    if (light->spot_along)
      s.shadows->light = spot_along(scene, light->settings.light.direction, light->settings.light.fov,
                                    light->settings.light.size);
  }
  described = {scene.name, scene.meshes.size(), scene.triangle_count()};
  s.camera = camera_params(args, scene);
  std::optional<gl::EglContext> context;
  try {
    context.emplace();
  } catch (const gl::GlError& e) {
    throw DataError(std::string("render: no usable OpenGL: ") + e.what());
  }
  RenderResult r = render_scene(scene, s);
  if (light && light->settings.read_back) accuracy = shadow_error(scene, s, r, light->error_receivers);
  return r;
}

std::vector<float> as_floats(const std::vector<std::uint32_t>& v) { return {v.begin(), v.end()}; }

std::vector<HeatmapOutput> write_heatmaps(const std::vector<HeatmapRequest>& requests, const RenderResult& r, Extent size) {
  std::vector<HeatmapOutput> out;
  for (const HeatmapRequest& h : requests) {
    std::vector<float> values;
    std::string title;
    if (h.kind == "depth") {
      values = as_floats(r.pixel_fragments);
      title = "fragments per pixel";
    } else if (h.kind == "age") {
      values = as_floats(max_age_per_pixel(*r.ha_buffer()));
      title = "max age per pixel";
    } else if (h.kind == "shadow") {
      values = r.shadow_map;  // -1 where no surface: drawn as 0, the ramp's dark end
      for (float& v : values) v = std::max(v, 0.0f);
      title = "light transmittance T at the nearest surface";
    } else {
      values = as_floats(r.pixel_culled);
      title = "culled fragments per pixel";
    }
    const HeatmapRange range = write_heatmap(h.path, size, values, title);
    out.push_back({h.kind, h.path, range.max});
  }
  return out;
}

// One warning line for fragments lost over all frames; exit 1 when lossless
// mode could not keep them; a warning when nothing reached the screen.
int report_render_losses(const RenderSettings& s, const RenderResult& r) {
  Counters total;
  std::uint64_t rejected = 0;
  for (const FrameStats& f : r.frames) {
    total += f.counters;
    rejected += f.opaque_rejected;
  }
  if (total.fragments + rejected == 0)
    std::fprintf(stderr, "habuffer render: warning: no transparent fragment reached the screen in %zu frame%s: the "
                         "scene is out of view, fully opaque or degenerate\n",
                 r.frames.size(), r.frames.size() == 1 ? "" : "s");
  if (r.light && r.light->counters.fragments == 0)
    std::fprintf(stderr, "habuffer render: warning: the light's view holds no fragment: nothing casts a shadow\n");
  // A record shadows a receiver only when nearer by more than the bias: a bias
  // of the whole depth range (a scene flat across the light, or a slope large
  // for its depth) leaves no shadow to cast.
  if (r.light && s.shadows && r.light->bias_codes >= RecordLayout(Layout::L64, s.shadows->age_bits).max_code())
    std::fprintf(stderr,
                 "habuffer render: warning: the shadow bias (%u depth codes, --shadow-slope %g) covers the light's "
                 "whole depth range over the scene: nothing can cast a shadow\n",
                 r.light->bias_codes, static_cast<double>(s.shadows->max_slope));
  if (r.light && r.light->counters.failures() > 0)
    std::fprintf(stderr,
                 "habuffer render: warning: the light buffer lost %llu of %llu fragments (table %s): shadows are "
                 "lighter where they were; %s\n",
                 static_cast<unsigned long long>(r.light->counters.failures()),
                 static_cast<unsigned long long>(r.light->counters.fragments), r.light->table.str().c_str(),
                 r.light->too_deep ? ("light pixel (" + std::to_string(r.light->too_deep->pixel.x) + ", " +
                                      std::to_string(r.light->too_deep->pixel.y) + ") receives " +
                                      std::to_string(r.light->too_deep->records) +
                                      " fragments, more than any table holds (AMAX): use --light-cull")
                                         .c_str()
                 : r.light->counters.failed_age > 0 ? "a light pixel is deeper than AMAX: use --light-cull"
                                                    : "use --light-table auto or a larger one");
  const std::string frames = r.frames.size() == 1 ? "" : " over " + std::to_string(r.frames.size()) + " frames";
  // Age failures from a pixel deeper than AMAX are not the buffers' size:
  // say which pixel and what age bits would hold it.
  const std::string too_deep = r.too_deep ? too_deep_message(*r.too_deep, s.config.age_bits) : "";
  if (s.lossless && total.failures() > 0) {
    report_lossless_failure("habuffer render", total,
                            frames + " after up to " + std::to_string(s.max_attempts) + " attempts per frame" +
                                lossless_failure_reason(too_deep, r.growth_limited, s.max_attempts, s.technique));
    return 1;
  }
  warn_losses("habuffer render", total, frames, too_deep.empty() ? lossless_hint(s.technique) : too_deep);
  return 0;
}

}  // namespace

namespace {

// A recorded stream, rendered on the CPU path (the scene options refused).
RenderResult render_stream(const Args& args, RenderSettings& s, SceneDescription& described) {
  if (s.path != RenderPath::Cpu && args.has("path"))
    throw UsageError("--fragments renders on the CPU path: drop --path " + args.str("path"));
  for (const char* scene_only : {"frames", "yaw", "pitch", "fov", "opacity", "count", "spread", "order", "scene-seed",
                                 "opaque-meshes"})
    if (args.has(scene_only))
      throw UsageError(std::string("option --") + scene_only + " applies to --scene, not to --fragments");
  s.path = RenderPath::Cpu;
  const std::vector<Fragment> fragments = read_fragments(args.required("fragments"), s.config.screen);
  described = {args.required("fragments"), 0, 0};
  return render_fragments(fragments, s);
}

// The image, reference and heat maps the options ask for, each written whole.
void write_render_outputs(const Args& args, const RenderSettings& s, const RenderResult& r,
                          const std::vector<HeatmapRequest>& heatmaps, RenderOutputs& outputs) {
  if (s.config.layout == Layout::L32 && args.has("out"))
    std::fprintf(stderr, "habuffer render: note: L32 records carry no colour; the image shows the opaque parts only, "
                         "the stats and heat maps show the lists\n");
  if (args.has("out")) {
    outputs.image = args.required("out");
    write_image(outputs.image, r.image);
  }
  outputs.heatmaps = write_heatmaps(heatmaps, r, s.config.screen);
  if (args.has("reference") || args.has("error")) {
    const Image reference = reference_image(r.fragments, s.config.screen, r.backgrounds, s.config.samples);
    outputs.error = compare_pixels(r.image, reference);
    if (args.has("reference")) {
      outputs.reference = args.required("reference");
      write_image(outputs.reference, reference);
      if (!outputs.image.empty()) outputs.reference_difference = compare_images(outputs.image, outputs.reference);
    }
  }
}

}  // namespace

int run_render(const std::vector<std::string>& argv) {
  if (print_help(argv, render_spec().help() + technique_help())) return 0;
  const Args args(argv, render_spec());
  if (args.has("scene") == args.has("fragments")) throw UsageError("give exactly one of --scene and --fragments");
  if (!args.has("out") && !args.has("stats")) throw UsageError("give --out IMAGE (and/or --stats STATS.json)");
  RenderSettings s = parse_settings(args);
  check_camera_args(args);
  refuse_scene_options_that_do_not_apply(args);
  const std::vector<std::string> opaque_meshes =
      args.has("opaque-meshes") ? args.list("opaque-meshes", "") : std::vector<std::string>{};
  const std::optional<LightArgs> light = parse_light(args);
  if (light && s.config.layout == Layout::L32)
    throw UsageError("option --shadows needs --layout 64 (the view's shaders read the light's 64-bit records)");
  const std::vector<HeatmapRequest> heatmaps = parse_heatmaps(args, s.technique);
  check_image_outputs(args, heatmaps);
  for (const HeatmapRequest& h : heatmaps) s.per_pixel_culled |= h.kind == "culled";
  s.keep_fragments = args.has("reference") || args.has("error");
  s.count_slot_writes = args.has("slot-writes");
  if (light && light->settings.read_back) s.keep_fragments = true;  // the transparent receivers
  SceneDescription described;
  RenderResult r;
  RenderOutputs outputs;
  if (args.has("fragments")) {
    r = render_stream(args, s, described);
  } else {
    ProgressBar progress = ProgressBar::for_terminal("habuffer render", "frames", args.has("quiet") || s.frames == 1);
    s.on_progress = progress.callback();
    r = render_with_gl(args, opaque_meshes, light, s, described, outputs.shadow_error);
    s.on_progress = nullptr;
  }
  write_render_outputs(args, s, r, heatmaps, outputs);
  const RenderSummary summary = summarize_render(described, s, r, outputs);
  if (args.has("stats")) {
    outputs.stats = args.required("stats");
    write_render_stats(outputs.stats, summary);
  }
  if (!args.has("quiet")) print_render_summary(summary, outputs);
  return report_render_losses(s, r);
}

}  // namespace habuffer::cli
