#include "view_run.h"

#include <epoxy/gl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "habuffer/counters.h"
#include "habuffer/json_writer.h"
#include "habuffer/pixel_depth.h"
#include "habuffer/render/image.h"
#include "habuffer/technique_descriptor.h"
#include "heat_overlay.h"
#include "loss_report.h"
#include "oit_session.h"
#include "scene_options.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/scene.h"
#include "shadow_light.h"
#include "technique_edit.h"
#include "view_panel.h"
#include "view_window.h"

namespace habuffer::view {
namespace {

// Resident memory of this process (KiB), from /proc/self/statm.
std::uint64_t resident_kib() {
  std::ifstream statm("/proc/self/statm");
  std::uint64_t size = 0, resident = 0;
  statm >> size >> resident;
  return resident * static_cast<std::uint64_t>(sysconf(_SC_PAGESIZE)) / 1024;
}

// Live GL objects of each kind: the names in use among the first `probe`
// (GL names are small integers, reused once freed), a leak check that needs
// no bookkeeping of ours.
struct LiveObjects {
  std::uint64_t buffers = 0, textures = 0, framebuffers = 0, programs = 0, vertex_arrays = 0, queries = 0;
  [[nodiscard]] std::uint64_t total() const {
    return buffers + textures + framebuffers + programs + vertex_arrays + queries;
  }
};

LiveObjects live_objects(GLuint probe = 1u << 14) {
  LiveObjects o;
  for (GLuint n = 1; n <= probe; ++n) {
    o.buffers += glIsBuffer(n);
    o.textures += glIsTexture(n);
    o.framebuffers += glIsFramebuffer(n);
    o.programs += glIsProgram(n);
    o.vertex_arrays += glIsVertexArray(n);
    o.queries += glIsQuery(n);
  }
  return o;
}

void write_objects(JsonWriter& j, const LiveObjects& o) {
  j.begin_object()
      .field("buffers", o.buffers)
      .field("textures", o.textures)
      .field("framebuffers", o.framebuffers)
      .field("programs", o.programs)
      .field("vertex_arrays", o.vertex_arrays)
      .field("queries", o.queries)
      .field("total", o.total())
      .end_object();
}

// The window's colour (what the user sees, panel included), row 0 at the bottom.
Image read_window(Extent size) {
  std::vector<float> rgba(4 * size.area());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, static_cast<GLsizei>(size.x), static_cast<GLsizei>(size.y), GL_RGBA, GL_FLOAT, rgba.data());
  Image image{size, std::vector<glm::vec4>(size.area())};
  for (std::size_t i = 0; i < image.pixels.size(); ++i)
    image.pixels[i] = glm::vec4(rgba[4 * i], rgba[4 * i + 1], rgba[4 * i + 2], 1.0f);
  return image;
}

// The next technique of the registry after `t` (wrapping).
Technique next_technique(Technique t) {
  const auto all = technique_registry();
  for (std::size_t i = 0; i < all.size(); ++i)
    if (all[i]->technique == t) return all[(i + 1) % all.size()]->technique;
  return all.front()->technique;
}

Overlay next_overlay(Overlay o) { return static_cast<Overlay>((static_cast<int>(o) + 1) % 5); }

// One frame's line of the report.
struct FrameRow {
  std::string technique, screen;
  FrameFigures figures;
  std::uint64_t rss_kib = 0;  ///< resident memory after the frame
};

struct RunTally {
  std::uint64_t switches = 0, refused = 0, resizes = 0, gl_errors = 0;
  /// Per technique, the live GL objects the first and the last time it ran
  /// after the warm-up (a technique's own buffers differ from another's).
  std::map<std::string, std::pair<LiveObjects, LiveObjects>> objects;
  std::string first_refusal;
  Counters total;                       ///< every frame's final gather, summed
  std::optional<PixelDepth> too_deep;   ///< the latest pixel deeper than AMAX that stopped growth
  bool growth_limited = false;
};

class ViewRun {
 public:
  ViewRun(const ViewSettings& s, const Scene& scene)
      : s_(s),
        scene_(scene),
        window_(s.window, "habuffer-view: " + scene.name),
        meshes_(scene),
        session_(meshes_, screen_config(s.technique, window_.framebuffer()), s.offsets,
                 SessionOptions{s.policy, s.lossless, s.max_attempts}),
        overlay_(s.overlay),
        gui_(s.gui) {
    camera_.yaw = s.yaw.value_or(scene.default_yaw);
    camera_.pitch = s.pitch.value_or(scene.default_pitch);
    camera_.fov = s.fov;
    light_angles(s.light_dir, panel_.light_azimuth, panel_.light_elevation);
    if (s.shadows) switch_shadows(true, s.light_dir, true);
    if (window_.framebuffer() != s.window)
      std::fprintf(stderr, "habuffer-view: the window system gave a %s framebuffer, not %s\n",
                   window_.framebuffer().str().c_str(), s.window.str().c_str());
  }

  int run() {
    const std::uint64_t warm_frame = s_.frames / 5;
    for (std::uint32_t frame = 0; s_.frames == 0 || frame < s_.frames; ++frame) {
      if (window_.should_close()) {
        if (s_.frames > 0) {
          std::fprintf(stderr, "habuffer-view: the window closed at frame %u of %u: no outputs written\n", frame,
                       s_.frames);
          return 1;
        }
        break;
      }
      const bool last = s_.frames != 0 && frame + 1 == s_.frames;
      scripted_steps(frame);
      handle_input(window_.poll());
      follow_window();
      const FrameFigures f = draw_frame(last);
      tally_.total += f.counters;
      if (f.too_deep) tally_.too_deep = f.too_deep;
      tally_.growth_limited = tally_.growth_limited || f.growth_limited;
      if (!s_.report.empty()) rows_.push_back({to_string(session_.config().technique), session_.driver().screen().str(), f, resident_kib()});
      if (!s_.report.empty() && frame >= warm_frame) {
        const LiveObjects live = live_objects();
        const auto [it, first] = tally_.objects.try_emplace(to_string(session_.config().technique), live, live);
        if (!first) it->second.second = live;
      }
      if (last) finish(f);
      window_.swap();
    }
    if (tally_.refused > 0)
      std::fprintf(stderr, "habuffer-view: %llu scripted %s refused; the first: %s\n",
                   static_cast<unsigned long long>(tally_.refused), tally_.refused == 1 ? "change" : "changes",
                   tally_.first_refusal.c_str());
    if (tally_.gl_errors > 0)
      std::fprintf(stderr, "habuffer-view: %llu GL errors\n", static_cast<unsigned long long>(tally_.gl_errors));
    const bool lossless_failed = s_.frames > 0 && report_losses();
    return tally_.refused == 0 && tally_.gl_errors == 0 && !lossless_failed ? 0 : 1;
  }

  // A scripted run's losses on stderr, as render says them (SPEC invariant
  // 1): a warning, or with --lossless the failure it is (returns true).
  bool report_losses() const {
    const Counters& total = tally_.total;
    if (lost_fragments(total) == 0) return false;  // warn_losses says nothing then either
    const std::string frames = s_.frames == 1 ? "" : " over " + std::to_string(s_.frames) + " frames";
    const Technique t = session_.config().technique;
    const std::string too_deep =
        tally_.too_deep ? too_deep_message(*tally_.too_deep, session_.config().buffer.age_bits) : "";
    if (s_.lossless && total.failures() > 0) {
      cli::report_lossless_failure("habuffer-view", total,
                                   frames + " after up to " + std::to_string(s_.max_attempts) + " attempts per frame" +
                                       cli::lossless_failure_reason(too_deep, tally_.growth_limited, s_.max_attempts, t));
      return true;
    }
    cli::warn_losses("habuffer-view", total, frames, too_deep.empty() ? cli::lossless_hint(t) : too_deep);
    return false;
  }

 private:
  static TechniqueConfig screen_config(TechniqueConfig c, Extent screen) {
    c.buffer.screen = screen;
    return c;
  }

  void scripted_steps(std::uint32_t frame) {
    for (const ScriptedResize& r : s_.resizes)
      if (r.frame == frame) {
        window_.resize(r.size);
        ++tally_.resizes;
      }
    if (tally_.switches < s_.cycle && frame > 0) apply(with_technique(session_.config(), next_technique(session_.config().technique)), true);
  }

  void handle_input(const InputEvents& e) {
    // The camera changes only by input, within frame_scene's range (render's):
    // a --pitch 90 or --fov 150 given on the command line stays as given.
    if (e.drag_x != 0) camera_.yaw = std::remainder(camera_.yaw + static_cast<float>(e.drag_x) * 0.3f, 360.0f);
    if (e.drag_y != 0)
      camera_.pitch = std::clamp(camera_.pitch - static_cast<float>(e.drag_y) * 0.3f, -kMaxPitch, kMaxPitch);
    if (e.scroll != 0)
      camera_.fov = std::clamp(camera_.fov * std::pow(0.9f, static_cast<float>(e.scroll)), kMinFov + 1.0f, kMaxFov - 1.0f);
    if (e.next_overlay) overlay_ = next_overlay(overlay_);
    if (e.toggle_gui) gui_ = !gui_;
    if (e.next_technique) apply(with_technique(session_.config(), next_technique(session_.config().technique)), false);
    psnr_requested_ = psnr_requested_ || e.psnr;
  }

  void apply(const TechniqueConfig& c, bool scripted) {
    const std::string refusal = session_.reconfigure(c);
    panel_.refusal = refusal;
    panel_.edits.clear();
    panel_.psnr.reset();
    if (!scripted) return;
    ++tally_.switches;
    if (!refusal.empty() && tally_.refused++ == 0) tally_.first_refusal = refusal;
  }

  // Shadows on (a light along `direction`, gathered now) or off. A refusal
  // (a multisampled or 32-bit view) is shown, or with `scripted` thrown.
  void switch_shadows(bool on, glm::vec3 direction, bool scripted) {
    std::string refusal;
    try {
      if (!on) {
        refusal = session_.set_shadows(nullptr);
        if (refusal.empty()) light_.reset();
      } else {
        auto light = std::make_unique<ShadowLight>(scene_, direction, s_.light_size, session_.driver().bindings());
        light->build();
        refusal = session_.set_shadows(light.get());
        if (refusal.empty()) light_ = std::move(light);  // the old light goes once the passes no longer use it
      }
    } catch (const SceneError& e) {
      refusal = e.what();
    } catch (const std::invalid_argument& e) {
      refusal = e.what();
    } catch (const gl::GlError& e) {
      refusal = e.what();
    }
    if (!refusal.empty() && scripted) throw std::runtime_error("--shadows: " + refusal);
    if (light_ && light_->figures().failures > 0 && refusal.empty())
      refusal = "the light buffer dropped " + std::to_string(light_->figures().failures) +
                " fragments after 16 gathers: shadows are lighter than they are";
    panel_.refusal = refusal;
    panel_.psnr.reset();
  }

  void follow_window() {
    const Extent fb = window_.framebuffer();
    if (fb.area() == 0 || fb == session_.driver().screen() || fb == refused_screen_) return;  // minimized, unchanged
    try {
      session_.resize(fb);
      refused_screen_ = Extent{};
    } catch (const std::invalid_argument& e) {
      refuse_screen(fb, e.what());
    } catch (const gl::GlError& e) {
      refuse_screen(fb, e.what());
    }
    panel_.psnr.reset();
  }

  // A window the library cannot follow: the view keeps its size (drawn in
  // the window's corner) and says why, once for that size.
  void refuse_screen(Extent fb, const std::string& why) {
    refused_screen_ = fb;
    panel_.refusal = "window " + fb.str() + ": " + why;
    if (s_.frames > 0 && tally_.refused++ == 0) tally_.first_refusal = panel_.refusal;
  }

  FrameFigures draw_frame(bool last) {
    session_.count_pixels(overlay_ == Overlay::Depth || overlay_ == Overlay::Culled);
    const Extent screen = session_.driver().screen();
    const Camera camera = frame_scene(scene_, camera_, screen);
    const FrameFigures f = session_.frame(camera, s_.background);
    if (psnr_requested_ || (last && s_.psnr)) {
      panel_.psnr = session_.reference_psnr(camera, s_.background);
      psnr_requested_ = false;
    }
    // The scene image into the part of the window the panel leaves free,
    // then the overlay over it and the panel beside it.
    const Extent window = window_.framebuffer();
    const Placement place = scene_placement(screen, window);
    const ViewRect& rect = place.image;
    const float clear[4] = {s_.background.r, s_.background.g, s_.background.b, 1.0f};
    glClearNamedFramebufferfv(0, GL_COLOR, 0, clear);
    glEnable(GL_SCISSOR_TEST);  // the blit and the overlay stay in the free columns
    glScissor(place.clip.x, place.clip.y, static_cast<GLsizei>(place.clip.size.x), static_cast<GLsizei>(place.clip.size.y));
    const bool scaled = rect.size != screen;
    glBlitNamedFramebuffer(session_.passes().image_framebuffer(), 0, 0, 0, static_cast<GLint>(screen.x),
                           static_cast<GLint>(screen.y), rect.x, rect.y, rect.x + static_cast<GLint>(rect.size.x),
                           rect.y + static_cast<GLint>(rect.size.y), GL_COLOR_BUFFER_BIT, scaled ? GL_LINEAR : GL_NEAREST);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    draw_overlay(f, camera, screen, rect);
    glDisable(GL_SCISSOR_TEST);
    if (gui_) {
      window_.begin_gui();
      const PanelRequest request = draw_panel(panel_, session_.config(), f, light_.get(), overlay_);
      window_.end_gui();
      if (request.config) apply(*request.config, false);
      if (request.shadows) switch_shadows(*request.shadows, light_direction(panel_.light_azimuth, panel_.light_elevation), false);
      if (request.light && light_) switch_shadows(true, *request.light, false);
      psnr_requested_ = psnr_requested_ || request.psnr;
    }
    for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError()) ++tally_.gl_errors;
    return f;
  }

  // Where the scene image goes: centred on the widest run of columns the
  // panel left free last frame (the whole window without a panel), scaled so
  // that the square frame_scene fits the scene's bounds in (the screen's
  // narrower side, centred) fits that run, never enlarged; what overflows
  // the run is clipped (`clip`). The image itself (the screenshot) stays
  // the view at the screen's size.
  struct Placement {
    ViewRect image, clip;
  };
  [[nodiscard]] Placement scene_placement(Extent screen, Extent window) const {
    double from = 0.0, width = window.x;
    if (gui_ && panel_.covers_to > panel_.covers_from) {
      const double left = std::clamp<double>(panel_.covers_from, 0.0, window.x);
      const double right = std::clamp<double>(panel_.covers_to, 0.0, window.x);
      if (left >= window.x - right) {
        width = left;
      } else {
        from = right;
        width = window.x - right;
      }
      if (width < window.x / 4.0) {  // a panel over most of the window: the scene under it
        from = 0.0;
        width = window.x;
      }
    }
    const double side = std::min(screen.x, screen.y);
    const double scale = std::min({1.0, width / side, static_cast<double>(window.y) / screen.y});
    Placement p;
    p.image.size = {std::max<std::uint32_t>(1, static_cast<std::uint32_t>(std::lround(screen.x * scale))),
                    std::max<std::uint32_t>(1, static_cast<std::uint32_t>(std::lround(screen.y * scale)))};
    p.image.x = static_cast<int>(std::lround(from + (width - p.image.size.x) / 2.0));
    p.image.y = static_cast<int>(std::lround((window.y - static_cast<double>(p.image.size.y)) / 2.0));
    p.clip.x = static_cast<int>(from);
    p.clip.size = {static_cast<std::uint32_t>(width), window.y};
    return p;
  }

  void draw_overlay(const FrameFigures& f, const Camera& camera, Extent screen, ViewRect window) {
    switch (overlay_) {
      case Overlay::Depth:
      case Overlay::Culled: {
        const double full = std::max<double>(1.0, 2.0 * static_cast<double>(f.counters.fragments) /
                                                       static_cast<double>(std::max<std::uint64_t>(screen.area(), 1)));
        heat_.draw(session_.passes().counts_buffer(), overlay_ == Overlay::Depth ? 1 : 2, 2, screen,
                   overlay_ == Overlay::Depth ? 4.0 * full : full, window);
        break;
      }
      case Overlay::Age:
        if (uses_table(session_.config().technique)) {
          const std::vector<std::uint32_t> ages = session_.max_age_per_pixel();
          if (ages.size() == screen.area()) heat_.draw(ages, screen, std::max(f.max_age, 1u), window);
        }
        break;
      case Overlay::Shadow:
        if (light_) {
          light_->bind();
          const std::vector<std::uint32_t> t = session_.passes().transmittance_map(camera);
          glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
          heat_.draw(t, screen, 255.0, window);
        }
        break;
      case Overlay::None: break;
    }
  }

  static void write_row(JsonWriter& j, const FrameRow& row) {
    const FrameFigures& f = row.figures;
    j.begin_object()
        .field("technique", row.technique)
        .field("screen", row.screen)
        .field("fragments", f.counters.fragments)
        .field("stored", f.counters.stored())
        .field("failures", f.counters.failures())
        .field("load", f.load())
        .field("max_age", f.max_age)
        .field("attempts", static_cast<std::uint64_t>(f.attempts))
        .field("table", f.table.str())
        .field("memory_bytes", f.memory_bytes)
        .field("gather_gpu_ms", f.gather_ms)
        .field("resolve_gpu_ms", f.resolve_ms)
        .field("frame_ms", f.frame_ms)
        .field("rss_kib", row.rss_kib)
        .end_object();
  }

  void finish(const FrameFigures& f) {
    if (!s_.window_shot.empty()) write_image(s_.window_shot, read_window(window_.framebuffer()));
    if (!s_.screenshot.empty()) write_image(s_.screenshot, session_.passes().read_image());
    for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError()) ++tally_.gl_errors;
    if (s_.report.empty()) return;
    JsonWriter j;
    j.begin_object()
        .field("scene", scene_.name)
        .field("technique", to_string(session_.config().technique))
        .field("screen", session_.driver().screen().str())
        .field("frames", static_cast<std::uint64_t>(s_.frames))
        .field("technique_switches", tally_.switches)
        .field("switches_refused", tally_.refused)
        .field("resizes", tally_.resizes)
        .field("gl_errors", tally_.gl_errors)
        .field("fragments", f.counters.fragments)
        .field("failures", f.counters.failures())
        .field("shadows", light_ != nullptr);
    j.key("psnr");
    if (panel_.psnr)
      j.value(std::isinf(*panel_.psnr) ? std::string("inf") : std::to_string(*panel_.psnr));
    else
      j.value(std::string("not measured"));
    j.key("gl_objects").begin_object();
    for (const auto& [technique, seen] : tally_.objects) {
      j.key(technique).begin_object().key("first");
      write_objects(j, seen.first);
      j.key("last");
      write_objects(j, seen.second);
      j.end_object();
    }
    j.end_object();
    j.key("per_frame").begin_array();
    for (const FrameRow& row : rows_) write_row(j, row);
    j.end_array().end_object();
    j.save(s_.report);
  }

  const ViewSettings& s_;
  const Scene& scene_;
  ViewWindow window_;
  GpuMeshes meshes_;
  std::unique_ptr<ShadowLight> light_;  // before the session: destroyed after it
  OitSession session_;
  HeatOverlay heat_;
  CameraParams camera_;
  Overlay overlay_;
  bool gui_;
  bool psnr_requested_ = false;
  Extent refused_screen_;  // a window size the library refused (not retried)
  PanelState panel_;
  RunTally tally_;
  std::vector<FrameRow> rows_;
};

}  // namespace

int run_view(const ViewSettings& settings) {
  Scene scene = make_scene(settings.scene, settings.scene_options);
  cli::make_opaque(settings.opaque_meshes, scene);
  ViewRun run(settings, scene);
  return run.run();
}

}  // namespace habuffer::view
