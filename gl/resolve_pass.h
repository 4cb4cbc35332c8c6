// The resolve pass (SPEC 7 on the GPU): one full-screen triangle whose
// fragment shader walks each pixel's records front to back and composites
// them over the background into the bound framebuffer.
#pragma once

#include <string>
#include <utility>

#include <glm/vec3.hpp>

#include "gpu_timer.h"
#include "habuffer/extent.h"
#include "habuffer/gl/shader_program.h"

namespace habuffer::gl {

class ResolvePass {
 public:
  // Compiles the pass from its fragment shader (resolve_fragment()).
  ResolvePass(const std::string& fragment_source, const std::string& name);
  ~ResolvePass();
  ResolvePass(const ResolvePass&) = delete;
  ResolvePass& operator=(const ResolvePass&) = delete;

  // Needs the buffers bound and the caller's state guard. Returns {wall ms, GPU ms}.
  // background_texture: 0 for the uniform background, else a 2D texture read per pixel.
  std::pair<double, double> run(Extent screen, glm::vec3 background, unsigned background_texture, bool finish);

 private:
  ShaderProgram program_;
  GpuTimer timer_;
  unsigned vertex_array_ = 0;
};

}  // namespace habuffer::gl
