/// @file
/// CSG rendered from lossless sorted lists (seed 000, section 6.3): every
/// primitive (a closed mesh) gathered from the camera into an HA-buffer of
/// L64 records, data word primitive_id << 1 | exit (gl_FrontFacing: the
/// camera outside every primitive sees an entry as a front face), then
/// each pixel's list walked by habuffer/csg.h's csg_resolve. The visible
/// surface is shaded from the depth image the walk leaves (its normal from
/// the neighbouring pixels' positions), so the records need nothing more
/// than id and facing. The table is sized from a counting pass (an
/// occlusion query over every primitive) at load 0.5, and the build is
/// lossless: the table grows until
/// nothing is dropped, and a render that still lost a record throws (a
/// lost record is a wrong pixel, not a faint one).
#pragma once

#include <cstdint>
#include <vector>

#include "habuffer/camera.h"
#include "habuffer/csg.h"
#include "habuffer/fragment.h"
#include "habuffer/render/image.h"
#include "habuffer/scene.h"

namespace habuffer {

/// What render_csg runs with.
struct CsgRenderSettings {
  Extent screen{256, 256};  ///< pixels
  CameraParams camera;      ///< the view (framed on the primitives)
  bool cpu = false;         ///< GL captures, the CPU builds the lists (the same lists)
  std::uint32_t threads = 0;  ///< the CPU path's worker threads (0: the default)
};

/// Codes within which crossings of different primitives are one depth
/// (csg_resolve's `coincident`): coplanar faces, rounded by the GPU from
/// different triangles, land a few codes apart at 24 depth bits.
inline constexpr std::uint32_t kCsgCoincidentCodes = 16;

/// A CSG image and what it took.
struct CsgRender {
  Image image;                          ///< the visible surface shaded over white
  std::vector<std::int32_t> primitive;  ///< per pixel (row 0 at the bottom): the visible primitive, -1 for none
  std::vector<std::uint32_t> codes;     ///< per pixel: its depth code (0 for none)
  Camera camera;                        ///< the view
  Counters counters;                    ///< the gather's (duplicates: merged equal crossings)
  std::uint32_t attempts = 0;           ///< gathers (grown until nothing was dropped)
  std::uint64_t list_bytes = 0;         ///< the HA-buffer's storage
  double gather_ms = 0.0, resolve_ms = 0.0;
};

/// Renders `expression` over the meshes of `primitives` (mesh i is primitive
/// i, the expression's names in the same order). Needs a current OpenGL 4.5
/// context with 64-bit shader integers. Throws CsgError (an expression over
/// another count of primitives), SceneError (the camera), GlError (limits,
/// or records lost after every growth).
CsgRender render_csg(const Scene& primitives, const CsgExpression& expression, const CsgRenderSettings& settings);

/// The reference: at each pixel centre, every primitive's crossings of the
/// camera's ray in double (depth codes of their exact t), walked by the
/// same csg_resolve. `band` receives the pixels whose visible primitive
/// differs on a ray 1/256 pixel beside the centre's (an edge within the
/// rasterizer's snapping) or whose visible crossing lies within 4 codes of
/// another primitive's (rounding decides).
std::vector<std::int32_t> csg_reference(const Scene& primitives, const CsgExpression& expression, const Camera& camera,
                                        Extent screen, std::vector<bool>* band = nullptr);

/// A render against csg_reference: pixels whose visible primitive differs outside the band, and the band's size.
struct CsgCheck {
  std::uint64_t mismatches = 0, band = 0;
};
/// Compares `render` (of `expression` over `primitives`) with csg_reference at its camera.
CsgCheck check_csg(const Scene& primitives, const CsgExpression& expression, const CsgRender& render, Extent screen);

}  // namespace habuffer
