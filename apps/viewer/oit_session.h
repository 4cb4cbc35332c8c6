/// @file
/// One technique's order-independent transparency in habuffer-view: the
/// GlFrameDriver made from a TechniqueConfig by the technique factory
/// (make_gl_technique), the viewer's passes around it, and what a frame
/// shows (FrameFigures). Switching the technique or an option makes a new
/// driver; a window resize calls the driver's resize_screen. A change the
/// library refuses leaves the running one as it was and says why.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "gpu_meshes.h"
#include "habuffer/gl/gl_frame_driver.h"
#include "habuffer/lossless_build.h"
#include "habuffer/pixel_depth.h"
#include "habuffer/render/image.h"
#include "habuffer/technique.h"
#include "shadow_light.h"
#include "view_passes.h"

namespace habuffer::view {

/// What one frame did, for the panel and the report.
struct FrameFigures {
  std::uint64_t index = 0;
  Counters counters;             ///< the final gather's outcome tallies
  std::uint64_t capacity = 0;    ///< records the container could hold
  std::uint32_t max_age = 0;     ///< the largest cell of the max-age table (HA-buffer)
  std::uint64_t memory_bytes = 0;  ///< the technique's and the frame's buffers
  std::uint32_t attempts = 0;    ///< gathers (lossless mode)
  Extent table;                  ///< the HA-buffer's table
  /// Per pass, GPU time (ms): clear, count, gather, sort, resolve.
  double clear_ms = 0, count_ms = 0, gather_ms = 0, sort_ms = 0, resolve_ms = 0;
  double frame_ms = 0;           ///< wall clock of the whole frame (ms)
  /// A pixel deeper than AMAX the gather counted, when it stopped lossless
  /// growth (no table holds it; render's rule): the frame kept its table, lossy.
  std::optional<PixelDepth> too_deep;
  bool growth_limited = false;   ///< lossless growth reached this OpenGL's limits
  [[nodiscard]] double load() const {
    return capacity == 0 ? 0.0 : static_cast<double>(counters.stored()) / static_cast<double>(capacity);
  }
};

/// How the frames run besides the technique (GlFrameOptions' policy and attempts).
struct SessionOptions {
  ResizePolicy policy;
  bool lossless = false;
  std::uint32_t max_attempts = 1;  ///< with lossless
};

class OitSession {
 public:
  /// Makes the driver for `config` (its screen is the window's) and the passes.
  /// Throws std::invalid_argument or GlError naming what the library refused.
  OitSession(const GpuMeshes& meshes, TechniqueConfig config, OffsetSource offsets, SessionOptions options);
  ~OitSession();

  /// The technique as configured now.
  [[nodiscard]] const TechniqueConfig& config() const { return config_; }
  /// A new technique or options: a new driver; on a refusal (std::invalid_argument,
  /// GlError) the running one stays and the message is returned; empty on success.
  std::string reconfigure(TechniqueConfig config);
  /// The window's framebuffer changed: the driver's resize_screen and new
  /// passes. On a refusal (std::invalid_argument, GlError: the context's
  /// limits) everything stays at the old screen and the error propagates.
  void resize(Extent screen);
  /// Shades by `light` from now on (nullptr: no shadows): new passes, and
  /// the light bound before every frame. Returns the refusal (the view's
  /// module must read 64-bit records, one sample a pixel) or empty.
  std::string set_shadows(ShadowLight* light);
  [[nodiscard]] const ShadowLight* shadows() const { return light_; }
  /// Whether the gather counts fragments per pixel (the depth and culled
  /// heat maps); a change compiles the gather again.
  void count_pixels(bool on);
  /// One frame: the opaque pass, the driver's frame around the gather, the
  /// resolve into the scene image. With `capture`, the frame's fragments are
  /// kept for the exact reference (reference_psnr).
  FrameFigures frame(const Camera& camera, glm::vec3 background);
  /// PSNR (dB; infinite when equal) of the last frame's image against the
  /// exact reference of the same view: the same frame rendered again with a
  /// capturing driver, its fragments composited in double precision over the
  /// opaque colours. The running driver is kept.
  double reference_psnr(const Camera& camera, glm::vec3 background);
  /// Max age per pixel of the last frame (HA-buffer: read back), else empty.
  [[nodiscard]] std::vector<std::uint32_t> max_age_per_pixel() const;

  /// Whether frames may regather into a grown HA-buffer table (automatic
  /// sizing or --lossless, no early cull): the gather then counts each
  /// pixel's fragments, and a frame with a pixel deeper than AMAX grows
  /// nothing (FrameFigures::too_deep), as render's frames do.
  [[nodiscard]] bool guards_depth() const { return guards_depth(*driver_, config_); }

  [[nodiscard]] const ViewPasses& passes() const { return *passes_; }
  [[nodiscard]] ViewPasses& passes() { return *passes_; }
  [[nodiscard]] const gl::GlFrameDriver& driver() const { return *driver_; }

 private:
  std::unique_ptr<gl::GlFrameDriver> make_driver(const TechniqueConfig& config, bool capture) const;
  std::unique_ptr<ViewPasses> make_passes(const gl::GlFrameDriver& driver, const TechniqueConfig& config) const;
  FrameFigures run_frame(gl::GlFrameDriver& driver, ViewPasses& passes, const Camera& camera, glm::vec3 background);
  static bool guards_depth(const gl::GlFrameDriver& driver, const TechniqueConfig& config);

  const GpuMeshes& meshes_;
  TechniqueConfig config_;
  OffsetSource offsets_;
  SessionOptions options_;
  std::unique_ptr<gl::GlFrameDriver> driver_;
  std::unique_ptr<ViewPasses> passes_;
  ShadowLight* light_ = nullptr;  // owned by the run
  bool count_pixels_ = false;
  /// The running driver's last view with a pixel deeper than AMAX (its
  /// attempts limited to 1 while the view stays) and that pixel.
  std::optional<Camera> deep_view_;
  std::optional<PixelDepth> deep_pixel_;
};

}  // namespace habuffer::view
