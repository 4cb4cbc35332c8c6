/// @file
/// The blended baselines on the GPU: weighted blended OIT (wboit) and plain
/// over-blending in submission order (blend). No lists: the insert call
/// writes each fragment's term to fragment outputs and the fixed-function
/// blender accumulates it, in primitive order, into this container's
/// framebuffer (an RGBA32F accumulator; wboit adds an R32F revealage), which
/// the frame driver binds around the host's gather together with the blend
/// setup (GlStateGuard restores the host's). After each gather the
/// attachments are copied into storage buffers for the resolve and the
/// read-back (a CPU BlendedImage). Host shaders call habuffer_insert at most once
/// per invocation and discard where they call none
/// (techniques/blended/gl/glsl/blended_env.glsl); the compute entry draws a stream as points.
#pragma once

#include <memory>

#include "habuffer/gl/gl_technique.h"

namespace habuffer::gl {

/// The wboit and blend containers on the GPU (see the file comment).
class GlBlendedImage final : public GlTechnique {
 public:
  /// config.technique wboit or blend; throws std::invalid_argument for a bad
  /// config, GlError beyond the context's limits (its largest framebuffer).
  GlBlendedImage(const TechniqueConfig& config, AtomicMode mode, const GlBindings& bindings);
  /// Deletes the framebuffer, its textures and the copies.
  ~GlBlendedImage() override;

  /// The configuration, validated.
  [[nodiscard]] const TechniqueConfig& config() const { return config_; }

  /// GlTechnique interface (see gl_technique.h). before_gather and reset
  /// clear the accumulators (blend: colour 0, transmittance 1; wboit: sums
  /// 0, revealage 1); its Gather pass binds the framebuffer and the blend
  /// setup before the host's gather (enter_gather) and copies the
  /// attachments into the storage buffers after it (leave_gather); nothing
  /// is ever dropped, so grow is never needed and returns false.
  void write_params(GlParams& params) const override;
  void bind() const override;
  void begin_frame(FrameReport&, const GlFrameOptions&) override {}
  void before_gather() override { reset(); }
  void reset() override;
  bool grow(const FrameReport&, const GlFrameOptions&) override { return false; }
  /// Always 0: nothing is stored.
  [[nodiscard]] std::uint64_t capacity() const override { return 0; }
  /// The attachments and their storage-buffer copies: 32 bytes per pixel
  /// (blend, and the 4-byte revealage copy its resolve binds but never
  /// reads), 40 (wboit).
  [[nodiscard]] std::uint64_t memory_bytes() const override;
  [[nodiscard]] std::unique_ptr<FragmentBuffer> read_back() const override;

 protected:
  /// resize_screen (gl_technique.h): new accumulators of the new screen
  /// (cleared) and their storage-buffer copies, attached to the same
  /// framebuffer object, so gather_framebuffer() keeps its name.
  void change_screen(Extent screen) override;

 private:
  struct Gpu;
  /// The Gather pass, before the host's gather: the framebuffer and blend state.
  void enter_gather() const;
  /// The Gather pass, after it: the attachments copied to the storage buffers.
  void leave_gather() const;
  [[nodiscard]] bool weighted() const { return config_.technique == Technique::Wboit; }

  TechniqueConfig config_;
  std::unique_ptr<Gpu> gpu_;
};

}  // namespace habuffer::gl
