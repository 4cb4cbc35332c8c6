// The GL side of `habuffer render`: a scene's meshes in vertex buffers, the
// opaque pass (depth-tested, into a colour and a depth image) and the gather
// pass (transparent meshes through the GLSL module's ha_insert, fragments
// behind the opaque surfaces rejected and counted). Owns the state of the
// context it runs in (the render command's own).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "habuffer/camera.h"
#include "habuffer/gl/gl_frame_driver.h"
#include "habuffer/gl/shader_program.h"
#include "habuffer/scene.h"

namespace habuffer {

class SceneRenderer {
 public:
  // The renderer's shaders for an atomic mode, binding points and
  // technique, as compiled (no GL needed: the reference-compiler check
  // writes them out).
  struct Sources {
    std::string vertex, opaque_fragment, gather_fragment;
  };
  static Sources shader_sources(gl::AtomicMode mode, const gl::GlBindings& bindings,
                                Technique technique = Technique::Ha);

  // Compiles the gather shader for `buffer`'s technique, mode and binding points.
  SceneRenderer(const Scene& scene, Extent screen, const gl::GlFrameDriver& buffer);
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  void draw_opaque(const Camera& camera, glm::vec3 background);
  // The transparent meshes; call inside GlFrameDriver::frame (it may run twice
  // in one frame: the per-pixel counts start from zero each time).
  void gather(const Camera& camera);
  // The fragments a gather would insert (after opaque rejection), inserting
  // nothing: what an automatic table is sized from before the first frame.
  std::uint64_t count_fragments(const Camera& camera);

  // The floors every technique is measured against (benchmarks): plain
  // unsorted blending of the transparent fragments over the opaque pass's
  // colour (fixed-function, no lists), and one atomic add per fragment (to
  // the per-pixel counts of read_pixel_fragments). Returns the pass's
  // wall-clock milliseconds (to glFinish).
  double blend_floor(const Camera& camera);
  double atomic_floor(const Camera& camera);

  [[nodiscard]] unsigned opaque_colour_texture() const { return colour_; }
  // Row-major, row 0 at the bottom.
  [[nodiscard]] std::vector<glm::vec3> read_opaque_colour() const;
  [[nodiscard]] std::vector<std::uint32_t> read_pixel_fragments() const;
  [[nodiscard]] std::vector<std::uint32_t> read_pixel_culled() const;
  [[nodiscard]] std::uint64_t read_rejected() const;
  // ha_insert calls of the last gather (the per-pixel fragment counts summed).
  [[nodiscard]] std::uint64_t inserted() const;

 private:
  struct GpuMesh {
    unsigned vertex_array = 0, vertices = 0, indices = 0;
    std::int32_t count = 0;
    glm::vec3 colour;
    float opacity;
    bool opaque;  // drawn in the opaque pass
  };
  void draw_meshes(const gl::ShaderProgram& program, const Camera& camera, bool opaque) const;
  void run_gather(const Camera& camera, bool count_only);
  // The transparent meshes through `program` into `framebuffer`, the opaque depth image at unit 0.
  void draw_transparent(const gl::ShaderProgram& program, const Camera& camera, unsigned framebuffer) const;

  Extent screen_;
  std::vector<GpuMesh> meshes_;
  gl::ShaderProgram opaque_program_, gather_program_, blend_program_, atomic_floor_program_;
  unsigned opaque_framebuffer_ = 0, colour_ = 0, depth_ = 0, depth_buffer_ = 0;
  unsigned gather_framebuffer_ = 0, blend_framebuffer_ = 0;
  unsigned technique_framebuffer_ = 0;  // where the technique blends (wboit, blend), else 0
  unsigned pixel_fragments_ = 0, pixel_culled_ = 0, rejected_ = 0;
};

}  // namespace habuffer
