#include "habuffer/gl/light_mapping.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "habuffer/gl/gl_error.h"
#include "light_params.h"

namespace habuffer::gl {
namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

// A lookup of window depth that differs from t by more than this is refused
// (light_depth_mismatch): 4 depth codes at the default 24 depth bits.
constexpr double kWindowIsT = 0x1.0p-22;

}  // namespace

GlWindowDepth GlWindowDepth::current() {
  GLint mode = GL_NEGATIVE_ONE_TO_ONE;
  glGetIntegerv(GL_CLIP_DEPTH_MODE, &mode);
  GLfloat range[2] = {0.0f, 1.0f};
  glGetFloatv(GL_DEPTH_RANGE, range);
  return {mode == GL_ZERO_TO_ONE, range[0], range[1]};
}

GlLightDepthMap light_depth_map(const GlLightMapping& light, const GlWindowDepth& window) {
  const double n = light.near_plane, f = light.far_plane;
  if (!(std::isfinite(n) && std::isfinite(f) && n < f))
    throw std::invalid_argument("GlLightMapping: near_plane " + number(n) + " and far_plane " + number(f) +
                                " must be finite with near < far");
  const glm::mat4& p = light.projection;
  if (p[0][2] != 0.0f || p[1][2] != 0.0f || p[0][3] != 0.0f || p[1][3] != 0.0f)
    throw std::invalid_argument("GlLightMapping: the projection's depth or w depends on the eye's x or y "
                                "(row 2 or 3 of columns 0 and 1 not zero): window depth is no function of eye distance");
  const double r0 = window.range_near, r1 = window.range_far;
  if (!(r0 != r1))
    throw GlError("glDepthRange(" + number(r0) + ", " + number(r1) + ") is empty: a light pass needs window depths "
                  "that tell eye distances apart");
  // Window depth z = r0 + (r1 - r0) (s ndc + o), so ndc = u z + v; the
  // projection gives ndc = (-p22 e + p32) / (-p23 e + p33) at eye distance
  // e, so e = (p32 - ndc p33) / (p22 - ndc p23), and t = (e - n) / (f - n).
  const double s = window.zero_to_one ? 1.0 : 0.5, o = window.zero_to_one ? 0.0 : 0.5;
  const double u = 1.0 / ((r1 - r0) * s), v = -r0 * u - o / s;
  const double p22 = p[2][2], p32 = p[3][2], p23 = p[2][3], p33 = p[3][3];
  const double k = n * p23 - p33, span = f - n;
  const double a = k * u, b = k * v + (p32 - n * p22), c = -span * p23 * u, d = span * (p22 - p23 * v);
  const double scale = std::max(std::abs(c), std::abs(d));
  if (!(scale > 0.0 && std::isfinite(scale) && std::abs(a * d - b * c) > 0.0))
    throw std::invalid_argument("GlLightMapping: the projection's depth row maps no window depth to an eye "
                                "distance (row 2 or 3 degenerate)");
  return {static_cast<float>(a / scale), static_cast<float>(b / scale), static_cast<float>(c / scale),
          static_cast<float>(d / scale)};
}

std::string light_depth_mismatch(const GlGatherDepth& depth, const GlLightMapping& mapping) {
  if (depth.light)
    return *depth.light == mapping ? std::string()
                                   : "the light buffer was gathered for another light: its driver's "
                                     "GlFrameOptions::light differs from this GlLightMapping (a light that moved "
                                     "needs GlFrameDriver::set_light before its gather)";
  const std::string head = "the light buffer holds window depth (its driver has no GlFrameOptions::light), ";
  const std::string fix = ": set GlFrameOptions::light to this GlLightMapping";
  GlLightDepthMap map;
  try {
    map = light_depth_map(mapping, depth.window);
  } catch (const std::exception& e) {
    return head + "which this mapping cannot relate to its depth t (" + e.what() + ")" + fix;
  }
  for (const double z : {0.0, 0.5, 1.0}) {
    const double stored = depth.reversed ? 1.0 - z : z;
    if (!(std::abs(double{map(static_cast<float>(z))} - stored) <= kWindowIsT))
      return head + "which is not this light's linear depth t (a perspective light, or an orthographic one whose "
                    "projection spans other near and far planes than the mapping's)" + fix;
  }
  return {};
}

std::string light_module_defines(const std::optional<GlLightMapping>& light) {
  return light ? "#define HABUFFER_LIGHT_GATHER\n" : "";
}

void write_light_params(const std::optional<GlLightMapping>& light, const std::optional<GlGatherDepth>& recorded,
                        GlParams& params) {
  params.habuffer_light_gather = 0;
  if (!light) return;
  const GlLightDepthMap map = light_depth_map(*light, recorded ? recorded->window : GlWindowDepth{});
  params.habuffer_light_gather = 1;
  params.habuffer_light_near = light->near_plane;
  params.habuffer_light_far = light->far_plane;
  params.habuffer_light_a = map.a;
  params.habuffer_light_b = map.b;
  params.habuffer_light_c = map.c;
  params.habuffer_light_d = map.d;
}

GlGatherDepth gather_depth_now(const GlFrameOptions& options) {
  return {options.light, options.depth == DepthConvention::Reversed, GlWindowDepth::current()};
}

}  // namespace habuffer::gl
