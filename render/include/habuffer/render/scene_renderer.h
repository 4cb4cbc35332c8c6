/// @file
/// The GL side of `habuffer render`: a scene's meshes in vertex buffers, the
/// opaque pass (depth-tested, into a colour and a depth image) and the gather
/// pass (transparent meshes through the GLSL module's habuffer_insert, fragments
/// behind the opaque surfaces rejected and counted). Owns the state of the
/// context it runs in (the render command's own).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "habuffer/camera.h"
#include "habuffer/gl/gl_frame_driver.h"
#include "habuffer/gl/shadow_lookup.h"
#include "habuffer/gl/shader_program.h"
#include "habuffer/scene.h"

namespace habuffer {

/// How the view's passes read a light buffer (translucent shadows).
struct ShadowReceiving {
  gl::GlLightBindings bindings;  ///< where the light buffer and its block are bound
  bool pcf = false;              ///< T filtered over 2x2 light pixels; false: the nearest light pixel
};

/// A scene on the GPU and its passes (see the file comment); needs a current OpenGL 4.5 core context.
class SceneRenderer {
 public:
  /// What the gather pass counts per pixel besides inserting. Each count is
  /// a #define of the gather shader: one nobody reads costs no atomic per
  /// fragment. The per-pixel fragment counts are exact either way: without
  /// `fragments`, read_pixel_fragments() runs the counting pass for the last
  /// pass's camera when that camera's counts are not held already (none is
  /// needed after count_fragments of the camera just gathered).
  struct GatherCounts {
    bool fragments = false;  ///< fragments per pixel, in the inserting gather itself
    bool culled = false;     ///< fragments early cull rejected, per pixel (read_pixel_culled)
    /// What a gather for `buffer` must count: the fragments where the driver
    /// asks for the call count (GlFrameDriver::needs_call_count: the counts
    /// are then there at no extra pass), and the culled ones (none without early cull).
    static GatherCounts for_driver(const gl::GlFrameDriver& buffer);
  };

  /// The renderer's shaders for an atomic mode, binding points and
  /// technique, as compiled (no GL needed: the reference-compiler check
  /// writes them out); the gather with `counts`, in the module's default variant.
  struct Sources {
    std::string vertex, opaque_fragment, gather_fragment;  ///< the gather is also the counting pass
    std::string shadow_map_fragment;  ///< with shadows: the transmittance map's pass; else empty
  };
  /// See Sources; with `shadows`, as the constructor's (throws GlError for native32).
  static Sources shader_sources(gl::AtomicMode mode, const gl::GlBindings& bindings,
                                Technique technique = Technique::Ha, GatherCounts counts = {true, true},
                                std::optional<ShadowReceiving> shadows = std::nullopt, std::uint32_t samples = 1);

  /// Compiles the gather shader from `buffer`'s module (technique, mode,
  /// binding points and variant), counting GatherCounts::for_driver(buffer).
  /// `buffer` must outlive the renderer (its counting passes bind its blocks).
  SceneRenderer(const Scene& scene, Extent screen, const gl::GlFrameDriver& buffer);
  /// The same, counting `counts`. With `shadows`, the opaque pass and every
  /// inserted fragment are shaded by the light buffer bound at those points
  /// (translucent shadows: lit colour times the light's transmittance T,
  /// gl::GlShadowLookup::bind before each pass), and shadow_map_pass() is
  /// available. Throws GlError for a module in atomic mode native32 (the
  /// lookup reads 64-bit records).
  SceneRenderer(const Scene& scene, Extent screen, const gl::GlFrameDriver& buffer, GatherCounts counts,
                std::optional<ShadowReceiving> shadows = std::nullopt);
  /// Deletes every GL object it made.
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  /// The opaque meshes, depth-tested, over `background` into the colour and depth images the gather
  /// rejects against.
  void draw_opaque(const Camera& camera, glm::vec3 background);
  /// The transparent meshes; call inside GlFrameDriver::frame (it may run twice
  /// in one frame: the per-pixel counts start from zero each time).
  void gather(const Camera& camera);
  /// The fragments a gather would insert (after opaque rejection), inserting
  /// nothing: what an automatic table is sized from before the first frame.
  std::uint64_t count_fragments(const Camera& camera);

  /// The floors every technique is measured against (benchmarks): plain
  /// unsorted blending of the transparent fragments over the opaque pass's
  /// colour (fixed-function, no lists), and one atomic add per fragment (to
  /// the per-pixel counts of read_pixel_fragments). Returns the pass's
  /// wall-clock milliseconds (to glFinish).
  double blend_floor(const Camera& camera);
  /// One atomic add per fragment; see blend_floor.
  double atomic_floor(const Camera& camera);

  /// With shadows: the light's T at each pixel's nearest surface (every
  /// mesh, depth-tested; the light buffer bound), one lookup per covered
  /// pixel. Returns the pass's wall-clock milliseconds (to glFinish).
  /// Throws std::logic_error without shadows.
  double shadow_map_pass(const Camera& camera);
  /// The last shadow_map_pass's T per pixel, row 0 at the bottom; -1 where no surface covers the pixel.
  [[nodiscard]] std::vector<float> read_shadow_map() const;
  /// Whether the passes are shaded by a light buffer (the constructor's `shadows`).
  [[nodiscard]] bool shadows() const { return shadow_program_.has_value(); }

  /// The opaque pass's colour texture (GL name), the background the resolve composites over.
  [[nodiscard]] unsigned opaque_colour_texture() const { return colour_; }
  /// The opaque pass's colour, row-major, row 0 at the bottom.
  [[nodiscard]] std::vector<glm::vec3> read_opaque_colour() const;
  /// The opaque pass's t per pixel, row 0 at the bottom (2 where no opaque surface).
  [[nodiscard]] std::vector<float> read_opaque_depth() const;
  /// The fragments per pixel of the last gather, counting pass or atomic
  /// floor (a counting pass first where they were not counted).
  [[nodiscard]] std::vector<std::uint32_t> read_pixel_fragments();
  /// The last gather's early-culled fragments per pixel; empty unless GatherCounts::culled.
  [[nodiscard]] std::vector<std::uint32_t> read_pixel_culled() const;
  /// Fragments the last gather or counting pass rejected behind the opaque surfaces.
  [[nodiscard]] std::uint64_t read_rejected() const;
  /// habuffer_insert calls of the last gather (the per-pixel fragment counts summed).
  [[nodiscard]] std::uint64_t inserted();
  /// What the gather counts (fixed at construction).
  [[nodiscard]] const GatherCounts& gather_counts() const { return counts_; }

 private:
  struct GpuMesh {
    unsigned vertex_array = 0, vertices = 0, indices = 0;
    std::int32_t count = 0;
    glm::vec3 colour;
    float opacity;
    bool opaque;  // drawn in the opaque pass
  };
  void draw_meshes(const gl::ShaderProgram& program, const Camera& camera, bool opaque) const;
  // The counting pass (the gather program, inserting nothing): fragments per
  // pixel and rejected ones, with `buffer`'s blocks bound.
  void count(const Camera& camera);
  void bind_counts() const;
  // The transparent meshes through `program` into `framebuffer`, the opaque depth image at unit 0.
  void draw_transparent(const gl::ShaderProgram& program, const Camera& camera, unsigned framebuffer) const;

  Extent screen_;
  GatherCounts counts_;
  const gl::GlFrameDriver& buffer_;  // whose module the gather compiles
  std::vector<GpuMesh> meshes_;
  gl::ShaderProgram opaque_program_, gather_program_, blend_program_, atomic_floor_program_;
  std::optional<gl::ShaderProgram> shadow_program_;  // with shadows: T at the nearest surface
  unsigned shadow_map_ = 0, shadow_framebuffer_ = 0;
  unsigned opaque_framebuffer_ = 0, colour_ = 0, depth_ = 0, depth_buffer_ = 0;
  unsigned gather_framebuffer_ = 0, blend_framebuffer_ = 0;
  unsigned technique_framebuffer_ = 0;  // where the technique blends (wboit, blend), else 0
  // A multisampled screen (the buffer's samples above 1): the opaque pass's
  // attachments per sample, and the framebuffer of their per-pixel resolve.
  std::uint32_t samples_ = 1;
  unsigned ms_colour_ = 0, ms_depth_ = 0, ms_depth_buffer_ = 0, resolved_framebuffer_ = 0;
  unsigned pixel_fragments_ = 0, pixel_culled_ = 0, rejected_ = 0;
  // The camera of the last pass over the transparent meshes, the one whose
  // fragments pixel_fragments_ holds, and the opaque pass's (none before the first of each).
  std::optional<Camera> latest_, counted_, opaque_;
};

}  // namespace habuffer
