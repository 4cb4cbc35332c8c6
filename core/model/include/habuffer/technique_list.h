/// @file
/// The registry's one list: every technique the library builds, in the order
/// the CLI, the harness and the README list them. Adding a technique is its
/// folder (techniques/NAME/: its cpu/ and gl/ parts, declared by its own
/// CMakeLists.txt and added by techniques/CMakeLists.txt) and one line here:
///
///     X(Enumerator, folder_namespace)
///
/// The line makes the enumerator of habuffer::Technique and names the two
/// functions the technique's folders define, whose descriptors the
/// registries list (technique_descriptor.h, gl/technique_registry.h):
///
///     const habuffer::TechniqueDescriptor& habuffer::techniques::NS::descriptor();
///     const habuffer::gl::GlTechniqueDescriptor& habuffer::gl::techniques::NS::descriptor();
#pragma once

// clang-format off
#define HABUFFER_TECHNIQUES(X)   \
  X(Ha, ha)                      \
  X(Lists, lists)                \
  X(Arrays, arrays)              \
  X(SortedLists, sorted_lists)   \
  X(KBuffer, kbuffer)            \
  X(Wboit, wboit)                \
  X(Blend, blend)                \
  X(PagedLists, paged_lists)
// clang-format on
