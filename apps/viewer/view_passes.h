/// @file
/// habuffer-view's passes for one screen and one technique's frame driver,
/// as any host app writes them: the opaque pass into the host's colour and t
/// images (per sample on a multisampled screen), the gather that calls the
/// driver's module, and the image the driver resolves into (RGBA32F, the
/// scene without the panel). Made anew when the window or the technique
/// changes; deletes every GL object it made.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "gpu_meshes.h"
#include "habuffer/gl/gl_frame_driver.h"
#include "habuffer/gl/shadow_lookup.h"
#include "habuffer/render/image.h"

namespace habuffer::view {

/// Where the viewer's own shader-storage buffer is bound (below the library's points).
inline constexpr unsigned kCountsBinding = 2;

class ViewPasses {
 public:
  /// Compiles the gather from `driver`'s module (its samples, bindings and
  /// variant) and makes the images for `screen` (the driver's). With
  /// `shadows`, both passes shade by the light buffer bound at those points
  /// (R_SHADOWS: lit colour times the light's T). With `count_pixels`, the
  /// gather counts each pixel's fragments and early-culled ones
  /// (counts_buffer(): the heat maps), an atomic per fragment otherwise
  /// left out. Throws GlError.
  ViewPasses(const GpuMeshes& meshes, const gl::GlFrameDriver& driver, const gl::GlLightBindings* shadows = nullptr,
             bool count_pixels = false);
  ~ViewPasses();
  ViewPasses(const ViewPasses&) = delete;
  ViewPasses& operator=(const ViewPasses&) = delete;

  /// The opaque meshes over `background` into the colour and t images.
  void draw_opaque(const Camera& camera, glm::vec3 background);
  /// The transparent meshes through the module (inside GlFrameDriver::frame;
  /// it may run more than once a frame: the counts start from zero each time).
  void gather(const Camera& camera);
  /// With shadows: the light's T at each pixel's nearest surface (every mesh
  /// depth-tested; the light bound), as 1 + round(254 T), 0 where no surface:
  /// the shadow heat map. Empty without shadows.
  [[nodiscard]] std::vector<std::uint32_t> transmittance_map(const Camera& camera);
  /// habuffer_insert calls of the last gather (the frame driver's call count).
  [[nodiscard]] std::uint64_t calls() const;
  /// The framebuffer the driver resolves into (the scene image).
  [[nodiscard]] unsigned image_framebuffer() const { return image_framebuffer_; }
  /// The opaque colour per pixel, the background texture of the resolve.
  [[nodiscard]] unsigned opaque_colour() const { return colour_; }
  /// The counts buffer: word 0 the calls (where the driver asks for them),
  /// then two words a pixel, fragments and culled (with count_pixels; zero otherwise).
  [[nodiscard]] unsigned counts_buffer() const { return counts_; }
  /// Fragments per pixel of the last gather (row-major, row 0 at the bottom),
  /// where the passes count pixels; empty otherwise.
  [[nodiscard]] std::vector<std::uint32_t> read_pixel_fragments() const;
  [[nodiscard]] bool counts_pixels() const { return count_pixels_; }
  /// The scene image, row 0 at the bottom.
  [[nodiscard]] Image read_image() const;
  /// The opaque colour per pixel (the backgrounds of the exact reference).
  [[nodiscard]] std::vector<glm::vec3> read_opaque_colour() const;
  [[nodiscard]] Extent screen() const { return screen_; }

 private:
  void make_images(const gl::GlFrameDriver& driver, const gl::GlLightBindings* shadows);
  // The opaque meshes (and with `transparent_too` the others) into `framebuffer`, depth-tested.
  void draw_depth_tested(unsigned framebuffer, const gl::ShaderProgram& program, const Camera& camera,
                         bool transparent_too) const;
  void release();
  const GpuMeshes& meshes_;
  Extent screen_;
  std::uint32_t samples_;
  unsigned technique_framebuffer_;  // where a blending technique's gather draws (0: the gather framebuffer)
  gl::ShaderProgram opaque_program_, gather_program_;
  std::optional<gl::ShaderProgram> transmittance_program_;  // with shadows
  unsigned transmittance_ = 0, transmittance_framebuffer_ = 0;
  unsigned colour_ = 0, t_ = 0, depth_ = 0, opaque_framebuffer_ = 0;  // per pixel
  unsigned ms_colour_ = 0, ms_t_ = 0, ms_depth_ = 0, resolved_framebuffer_ = 0;  // per sample (samples above 1)
  unsigned gather_framebuffer_ = 0, image_ = 0, image_framebuffer_ = 0, counts_ = 0;
  bool count_pixels_ = false;
};

}  // namespace habuffer::view
