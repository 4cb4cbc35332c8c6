#include "habuffer/render/shadow_accuracy.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <glm/geometric.hpp>

#include "habuffer/parallel.h"
#include "habuffer/transmittance.h"

namespace habuffer {
namespace {

constexpr double kStep = 1.0 / 255.0;  // the goal's tolerance: one step of an 8-bit colour
// Depth codes of rounding in a light's t: t = (eye distance - near) / (far -
// near) in float32 carries the eye distance's rounding, up to ulp(far) =
// far * 2^-23, over the depth range, in codes; the transforms that make the
// eye distance take a few of those. Four of them, and at least 4 codes.
double code_slack(const LightView& light, const RecordLayout& layout) {
  const double near = light.camera.near_plane, far = light.camera.far_plane;
  return std::max(4.0, 4.0 * std::ldexp(far / (far - near), -23) * layout.max_code());
}
constexpr double kSnap = 1.0 / 128.0;  // light pixels: twice the rasterizers' sub-pixel step

// A receiving point: pixel centre and depth t in the view.
struct Receiver {
  double x, y, t;
};

std::vector<Receiver> receivers_of(const ShadowReceivers& r) {
  std::vector<Receiver> out;
  out.reserve(r.transparent.size() + r.opaque_depth.size() / 4);
  for (const Fragment& f : r.transparent) out.push_back({f.x + 0.5, f.y + 0.5, double{f.depth}});
  for (std::size_t i = 0; i < r.opaque_depth.size(); ++i)
    if (r.opaque_depth[i] >= 0.0f && r.opaque_depth[i] <= 1.0f)
      out.push_back({static_cast<double>(i % r.screen.x) + 0.5, static_cast<double>(i / r.screen.x) + 0.5,
                     double{r.opaque_depth[i]}});
  return out;
}

// World distance along the segment to the light of `codes` depth codes of
// the light at `point` (the light's t is linear in its eye depth).
double code_distance(const LightView& light, const RecordLayout& layout, glm::dvec3 point, double codes) {
  const double per_code = (double{light.camera.far_plane} - double{light.camera.near_plane}) / layout.max_code();
  double cosine = 1.0;
  if (!light.orthographic)
    cosine = std::max(1e-6, glm::dot(glm::normalize(point - glm::dvec3(light.position)), glm::dvec3(light.direction)));
  return std::max(0.0, codes) * per_code / cosine;
}

using Hits = std::vector<TransmittanceReference::Hit>;

double product_beyond(const Hits& hits, double self_distance) {
  double t = 1.0;
  for (const TransmittanceReference::Hit& h : hits)
    if (h.distance > self_distance) t *= 1.0 - h.alpha;
  return t;
}

// Whether rounding to depth codes may change what the lookup counts along
// these hits: a surface within `slack` (a distance) of the bias boundary, or
// two surfaces beyond it within `slack` of each other (at one code
// equal records merge, SPEC 10; near it, float rounding decides).
bool near_code_boundary(const Hits& hits, double window_lo, double window_hi, double slack) {
  for (std::size_t i = 0; i < hits.size(); ++i) {
    if (hits[i].distance >= window_lo && hits[i].distance <= window_hi) return true;
    if (i > 0 && hits[i - 1].distance > window_lo && hits[i].distance - hits[i - 1].distance < slack)
      return true;
  }
  return false;
}

ShadowTruth truth_at(const TransmittanceReference& reference, const LightView& light, const RecordLayout& layout,
                     std::uint32_t bias, glm::dvec3 p) {
  const double b = bias;
  ShadowTruth o;
  const Hits at_point = reference.hits(p, light);
  const double skipped = code_distance(light, layout, p, b + 0.5);
  o.reference = product_beyond(at_point, skipped);
  o.sample = light.sample(glm::vec3(p));
  if (const std::optional<LightSample>& s = o.sample) {
    // What the light pixel's records sampled: the ray through its centre, at the receiver's light depth.
    const glm::dvec3 centre = unproject(light.camera, light.size, glm::dvec2(s->pixel) + 0.5, double{s->depth});
    const Hits at_centre = reference.hits(centre, light);
    const double code = code_distance(light, layout, centre, 1.0);
    const double t_centre = product_beyond(at_centre, code * (b + 0.5));
    o.silhouette = std::abs(t_centre - o.reference) > kStep;
    // Self-shadowing: the centre ray meets a triangle of the receiver's own
    // surface (one its own ray skipped as itself) beyond the bias.
    for (const TransmittanceReference::Hit& own : at_point)
      if (own.distance <= skipped)
        for (const TransmittanceReference::Hit& h : at_centre)
          o.self_shadow = o.self_shadow || (h.triangle == own.triangle && h.distance > code * (b + 0.5));
    // An edge within the rasterizer's snapping of the centre (sub-pixel
    // precision: 1/256 of a pixel on llvmpipe and NVIDIA) may be covered or
    // not whatever the exact ray says: the band takes those too.
    for (const glm::dvec2 d : {glm::dvec2(kSnap, 0.0), glm::dvec2(-kSnap, 0.0), glm::dvec2(0.0, kSnap), glm::dvec2(0.0, -kSnap)}) {
      if (o.silhouette) break;
      const glm::dvec3 q = unproject(light.camera, light.size, glm::dvec2(s->pixel) + 0.5 + d, double{s->depth});
      o.silhouette = product_beyond(reference.hits(q, light), code * (b + 0.5)) != t_centre;
    }
    const double slack = code_slack(light, layout);
    o.depth = near_code_boundary(at_centre, code * (b - slack), code * (b + slack), code * slack);
  }
  return o;
}

}  // namespace

ShadowTruths shadow_truths(const TransmittanceReference& reference, const LightView& light, RecordLayout layout,
                           std::uint32_t bias, const ShadowReceivers& receivers, std::uint64_t max_receivers) {
  if (receivers.camera == nullptr) throw std::invalid_argument("shadow accuracy: the receivers have no camera");
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<Receiver> all = receivers_of(receivers);
  ShadowTruths truths;
  truths.stride = max_receivers == 0 || all.size() <= max_receivers
                      ? 1u
                      : static_cast<std::uint32_t>((all.size() + max_receivers - 1) / max_receivers);
  const std::size_t n = (all.size() + truths.stride - 1) / truths.stride;
  truths.at.resize(n);
  const std::uint32_t tasks = std::max<std::uint32_t>(1, std::min<std::uint32_t>(64, static_cast<std::uint32_t>(n)));
  fork_join(tasks, [&](std::uint32_t k) {
    for (std::size_t i = k; i < n; i += tasks) {
      const Receiver& r = all[i * truths.stride];
      const glm::dvec3 p = unproject(*receivers.camera, receivers.screen, {r.x, r.y}, r.t);
      truths.at[i] = truth_at(reference, light, layout, bias, p);
    }
  });
  truths.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return truths;
}

ShadowAccuracy score_shadows(const ShadowTruths& truths, const ShadowLookup& lookup) {
  const auto t0 = std::chrono::steady_clock::now();
  ShadowAccuracy a;
  a.stride = truths.stride;
  double sum = 0.0, sum_outside = 0.0;
  for (const ShadowTruth& o : truths.at) {
    // Outside the light's frustum: lit, as the GPU's lookup says.
    const double t = o.sample ? double{lookup(*o.sample)} : 1.0;
    const double error = std::abs(t - o.reference);
    ++a.receivers;
    a.silhouette_band += o.silhouette;
    a.depth_band += o.depth;
    a.self_shadow += o.self_shadow;
    sum += error * error;
    a.max_error = std::max(a.max_error, error);
    if (o.silhouette || o.depth) {
      ++a.band;
      continue;
    }
    a.within += error <= kStep * (1.0 + 1e-6);
    sum_outside += error * error;
    a.max_error_outside = std::max(a.max_error_outside, error);
  }
  const std::uint64_t outside = a.receivers - a.band;
  a.rmse = a.receivers > 0 ? std::sqrt(sum / static_cast<double>(a.receivers)) : 0.0;
  a.rmse_outside = outside > 0 ? std::sqrt(sum_outside / static_cast<double>(outside)) : 0.0;
  a.within_fraction = outside > 0 ? static_cast<double>(a.within) / static_cast<double>(outside) : 1.0;
  a.ms = truths.ms + std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return a;
}

ShadowLookup buffer_lookup(const FragmentBuffer& light_buffer, RecordLayout layout, std::uint32_t bias, bool pcf) {
  if (layout.layout() != Layout::L64)
    throw std::invalid_argument("shadow accuracy: a light buffer of L32 records carries no opacity");
  if (pcf)
    return [&light_buffer, layout, bias](const LightSample& at) {
      return transmittance_pcf(light_buffer, at.window.x, at.window.y, layout.depth_code(at.depth), bias);
    };
  return [&light_buffer, layout, bias](const LightSample& at) {
    return transmittance(light_buffer, at.pixel.x, at.pixel.y, layout.depth_code(at.depth), bias);
  };
}

ShadowAccuracy measure_shadow_accuracy(const TransmittanceReference& reference, const LightView& light,
                                       const FragmentBuffer& light_buffer, RecordLayout layout, std::uint32_t bias,
                                       const ShadowReceivers& receivers, std::uint64_t max_receivers, bool pcf) {
  const ShadowLookup lookup = buffer_lookup(light_buffer, layout, bias, pcf);
  return score_shadows(shadow_truths(reference, light, layout, bias, receivers, max_receivers), lookup);
}

}  // namespace habuffer
