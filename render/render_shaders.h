// The render command's shaders (embedded from render/shaders/ at build time).
#pragma once

namespace habuffer::render {

extern const char* const kSceneVertex;
extern const char* const kShading;
extern const char* const kOpaqueFragment;
extern const char* const kGatherFragment;
extern const char* const kBlendFragment;
extern const char* const kAtomicFloorFragment;

}  // namespace habuffer::render
