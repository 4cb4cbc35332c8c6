/// @file
/// habuffer-view's shaders, embedded at build time (cmake/EmbedText.cmake):
/// the scene's vertex shader, shading and opaque pass are `habuffer
/// render`'s own files (render/shaders/), so the two shade alike; the gather
/// and the overlay are the viewer's (apps/viewer/shaders/).
#pragma once

namespace habuffer::view {

extern const char* const kSceneVertex;     ///< render/shaders/scene.vert.glsl
extern const char* const kShading;         ///< render/shaders/shading.glsl
extern const char* const kOpaqueFragment;  ///< render/shaders/opaque.frag.glsl
extern const char* const kShadowMapFragment;  ///< render/shaders/shadow_map.frag.glsl: the light's T at the nearest surface
extern const char* const kGatherFragment;  ///< shaders/gather.frag.glsl
extern const char* const kOverlayVertex;   ///< shaders/overlay.vert.glsl
extern const char* const kOverlayFragment;  ///< shaders/overlay.frag.glsl

}  // namespace habuffer::view
