/// @file
/// Translucent shadow maps in `habuffer render` (seed 000, section 6): "A
/// HA-buffer is rendered from the light view and used as a shadow map ...
/// only updated when the light moves." The light pass gathers every mesh of
/// the scene from the light into an HA-buffer of L64 records (colour and
/// opacity), opaque meshes at opacity 1 through the same buffer rather than
/// into a depth map beside it: one structure, one lookup, and an opaque
/// record ends the walk with T = 0 exactly as a depth test would. The view's
/// passes then multiply each fragment's lit colour by the light's
/// transmittance T (habuffer/transmittance.h has the formula and the bias
/// rule; the lookup is gl/shadow_lookup.h's, the CPU path's walk bit for bit).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>

#include "habuffer/buffer_config.h"
#include "habuffer/fragment.h"
#include "habuffer/fragment_buffer.h"
#include "habuffer/gl/gl_info.h"
#include "habuffer/gl/shadow_lookup.h"
#include "habuffer/render/scene_renderer.h"
#include "habuffer/light_view.h"
#include "habuffer/pixel_depth.h"
#include "habuffer/resize_policy.h"
#include "habuffer/scene.h"

namespace habuffer {

/// The light and its buffer (`habuffer render --shadows`).
/// How the receivers read the light buffer.
enum class ShadowFilter {
  Nearest,  ///< T of the light pixel the point falls in
  Pcf       ///< 2x2 percentage-closer filtering: T of the four nearest pixels, bilinearly weighted
};

/// "nearest" or "pcf".
std::string to_string(ShadowFilter f);

struct ShadowSettings {
  LightParams light;   ///< direction or spot, and the map's pixels (the light buffer's screen)
  /// The light buffer's table; zero: automatic (sized from the light's
  /// counting pass and regathered into a grown table until nothing is
  /// dropped, at most 16 gathers).
  Extent table{};
  float early_cull_tau = 0.0f;  ///< the light buffer's early cull in [0, 1] (0: off; T then errs by at most 1 - tau)
  std::uint32_t age_bits = HABUFFER_DEFAULT_AGE_BITS;  ///< its records' age bits (BufferConfig's rule)
  /// The bias rule's largest slope (shadow_bias_codes): surfaces up to
  /// atan(max_slope) from facing the light never shadow themselves.
  float max_slope = 2.0f;
  /// How T is sampled; Pcf doubles the bias (its farthest tap lies twice as
  /// far as the nearest pixel's centre: transmittance_pcf).
  ShadowFilter filter = ShadowFilter::Nearest;
  /// Read the light buffer back after the frames (RenderResult::light_buffer:
  /// the accuracy check's records) and the view's opaque t per pixel.
  bool read_back = false;
  /// Capture the light pass's fragments (RenderResult::light_fragments: other
  /// light buffers built from the same stream, the shadow frontier).
  bool capture = false;
  /// Throws std::invalid_argument naming the field (an empty map, a bad
  /// slope: negative, not finite, or not below shadow_slope_limit of the
  /// map, halved under Pcf; tau outside [0, 1], BufferConfig's rules).
  void validate() const;
};

/// What the light pass built and what its lookups cost (RenderResult::light).
struct LightStats {
  Extent size;                 ///< the light map's pixels
  Extent table;                ///< the light buffer's table
  std::uint32_t builds = 0;    ///< light buffers gathered (1: the light never moved)
  std::uint32_t attempts = 0;  ///< gathers of the last build (more than 1: grown until nothing was dropped)
  Counters counters;           ///< the last build's insert outcomes
  double load_factor = 0.0;    ///< stored records / table slots
  std::uint64_t memory_bytes = 0;  ///< the light buffer's storage and the lookup's block
  std::uint32_t max_age = 0;   ///< the largest entry of its max-age table
  std::uint32_t bias_codes = 0;  ///< the receivers' bias, in depth codes
  double build_ms = 0.0;       ///< the last build, wall clock (its counting pass included)
  /// The transmittance map's pass: one lookup per covered view pixel (every
  /// mesh depth-tested), wall clock, and the pixels it covered.
  double lookup_ms = 0.0;
  std::uint64_t lookup_pixels = 0;
  LightView view;              ///< the light as framed on the scene
  /// Without early cull: a light pixel receiving more fragments than AMAX,
  /// which no table holds (so the automatic table did not grow for it).
  std::optional<PixelDepth> too_deep;
};

/// The light buffer of a render (see the file comment); needs a current
/// OpenGL 4.5 core context that has 64-bit shader integers.
class LightPass {
 public:
  /// Frames the light on `scene` and makes its buffer; builds nothing yet.
  /// `view` are the view technique's binding points, which the light
  /// buffer's lookup must not share. Throws SceneError (the light's
  /// parameters, frame_light), std::invalid_argument (the settings) or
  /// GlError (no 64-bit shader integers, the context's limits).
  LightPass(const Scene& scene, const ShadowSettings& settings, const gl::GlBindings& view);
  ~LightPass();
  LightPass(const LightPass&) = delete;
  LightPass& operator=(const LightPass&) = delete;

  /// Gathers the light buffer from the light's view (again only when the
  /// light moved: the render calls it once). Returns whether every fragment
  /// was stored (a given table may drop; an automatic one grows until none is).
  /// Throws GlError naming the light buffer (a table beyond this context's limits).
  bool build();
  /// Binds the light buffer and its block for the view's passes.
  void bind();
  /// Where and how the view's shaders read the light buffer (SceneRenderer's `shadows`).
  [[nodiscard]] ShadowReceiving receiving() const;
  /// The light buffer, read back to the CPU (tests: the CPU path's lookup over the same records).
  [[nodiscard]] std::unique_ptr<FragmentBuffer> read_back() const;
  /// The fragments the last build captured, in arrival order (empty unless ShadowSettings::capture).
  [[nodiscard]] std::vector<Fragment> read_capture() const;
  /// What was built so far (lookup_ms and lookup_pixels are the caller's).
  [[nodiscard]] const LightStats& stats() const { return stats_; }

 private:
  struct Gpu;
  bool gather();  // build's work
  std::unique_ptr<Gpu> gpu_;
  ShadowSettings settings_;
  LightStats stats_;
};

}  // namespace habuffer
