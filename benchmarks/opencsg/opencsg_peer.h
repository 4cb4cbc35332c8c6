/// @file
/// OpenCSG (Kirsch and Döllner's image-based CSG library, GPL-2+) as a
/// measured peer of habuffer's CSG from sorted depth lists. Benchmarks only:
/// this folder links OpenCSG into habuffer_csg_peers and habuffer_bench,
/// never into the library or the CLI.
///
/// OpenCSG renders a CSG expression in sum-of-products form (each product an
/// intersection of primitives less others) into the depth buffer, by the
/// Goldfeather algorithm (stencil parity counts: any primitive, convexity
/// stated per primitive) or SCS (sequenced convex subtraction: convex
/// primitives only). It needs a compatibility-profile context (fixed
/// function, ARB programs) and GLEW initialized on it; primitives draw with
/// the fixed-function matrices. After OpenCSG::render a shading pass with
/// GL_EQUAL writes each pixel's visible primitive, which the peer reads back
/// as the same per-pixel primitive image habuffer's CSG gives (CsgRender), so
/// both are checked against one ray caster (csg_reference).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "habuffer/camera.h"
#include "habuffer/extent.h"
#include "habuffer/scene.h"

namespace habuffer::peers {

enum class OpenCsgAlgorithm { Goldfeather, Scs };
/// An algorithm and how OpenCSG learns the depth complexity: occlusion
/// queries (OpenCSG::OcclusionQuery: counted per render), or none
/// (NoDepthComplexitySampling: the primitives' stated convexity bounds it).
struct OpenCsgMethod {
  OpenCsgAlgorithm algorithm = OpenCsgAlgorithm::Goldfeather;
  bool occlusion_queries = true;
  /// "goldfeather+occlusion", "scs+convexity", ...
  [[nodiscard]] std::string name() const;
};

/// One product: primitives (mesh indices) intersected, and primitives subtracted.
struct CsgProduct {
  std::vector<std::uint32_t> intersected, subtracted;
};

/// What one OpenCSG render gave.
struct OpenCsgRender {
  std::vector<std::int32_t> primitive;  ///< per pixel (row 0 at the bottom): the visible primitive, -1 for none
  double ms = 0.0;                      ///< OpenCSG's render and the shading pass, to glFinish
};

/// Makes a compatibility-profile OpenGL 4.5 context (EGL, headless) current
/// and initializes GLEW on it for OpenCSG; habuffer's GPU path runs in the
/// same context. Throws std::runtime_error naming what failed.
class CompatContext {
 public:
  CompatContext();
  ~CompatContext();
  CompatContext(const CompatContext&) = delete;
  CompatContext& operator=(const CompatContext&) = delete;

  /// Makes this context current until the guard goes, then the one current
  /// before (a benchmark binary whose other benchmarks keep their own).
  class Current {
   public:
    explicit Current(const CompatContext& c);
    ~Current();
    Current(const Current&) = delete;
    Current& operator=(const Current&) = delete;

   private:
    void* display_;
    void* context_;
    void* draw_;
    void* read_;
  };

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// The meshes of `primitives` in vertex buffers, rendered by OpenCSG (needs
/// the CompatContext current). `convexity` per mesh: the most front faces a
/// ray crosses (1 for convex meshes; Goldfeather reads it, SCS assumes 1).
class OpenCsgPeer {
 public:
  OpenCsgPeer(const Scene& primitives, std::vector<std::uint32_t> convexity, Extent screen);
  ~OpenCsgPeer();
  OpenCsgPeer(const OpenCsgPeer&) = delete;
  OpenCsgPeer& operator=(const OpenCsgPeer&) = delete;

  /// The union of `products` seen by `camera`.
  OpenCsgRender render(const std::vector<CsgProduct>& products, const Camera& camera, const OpenCsgMethod& method);

 private:
  struct Gpu;
  std::unique_ptr<Gpu> gpu_;
};

}  // namespace habuffer::peers
