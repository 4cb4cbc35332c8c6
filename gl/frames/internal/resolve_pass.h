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
  // Writes every colour channel of draw buffer 0 and no other draw buffer (prepare_full_screen_pass;
  // the caller's guard restores the host's mask and blend setup).
  std::pair<double, double> run(Extent screen, glm::vec3 background, unsigned background_texture, ClockMode clock);
  // The same over what the framebuffer holds: premultiplied (C, 1 - T)
  // blended with (GL_ONE, GL_ONE_MINUS_SRC_ALPHA), so a pixel with nothing
  // stored keeps its colour exactly.
  std::pair<double, double> run_over(Extent screen, ClockMode clock);

 private:
  std::pair<double, double> draw(Extent screen, glm::vec3 background, unsigned background_texture, bool over,
                                 ClockMode clock);

  ShaderProgram program_;
  GpuTimer timer_;
  unsigned vertex_array_ = 0;
  MadeOn made_on_;
};

}  // namespace habuffer::gl
