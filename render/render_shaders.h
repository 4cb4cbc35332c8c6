/// @file
/// The render command's shaders, embedded from render/shaders/ at build time
/// (habuffer_embed_text in cmake/EmbedText.cmake writes their definitions), so
/// the binary needs no shader files at run time.
#pragma once

namespace habuffer::render {

extern const char* const kSceneVertex;          ///< scene.vert.glsl: the meshes' vertex shader
extern const char* const kShading;              ///< shading.glsl: the shading the fragment shaders share
extern const char* const kOpaqueFragment;       ///< opaque.frag.glsl: the opaque pass
extern const char* const kGatherFragment;       ///< gather.frag.glsl: the gather (and counting) pass
extern const char* const kBlendFragment;        ///< blend.frag.glsl: the unsorted blending floor
extern const char* const kAtomicFloorFragment;  ///< atomic_floor.frag.glsl: the one-atomic-add floor
extern const char* const kShadowMapFragment;    ///< shadow_map.frag.glsl: T at each pixel's nearest surface

}  // namespace habuffer::render
