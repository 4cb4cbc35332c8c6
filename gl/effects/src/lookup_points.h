// What the two lookups a host shader appends (the light buffer's,
// shadow_lookup.h; the spatial hash's, gl_spatial_hash.h) share: shared GLSL
// instantiated under another prefix, and binding points of their own
// (three storage buffers and a uniform block) checked and written as
// #defines the same way.
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "habuffer/gl/gl_bindings.h"

namespace habuffer::gl {

// `source` with `from` replaced where it starts an identifier (and, when
// `whole`, only where it is the whole identifier).
std::string replace_identifiers(std::string_view source, std::string_view from, std::string_view to, bool whole);

// One binding point of a lookup's bindings struct: its member's name and value.
struct LookupPoint {
  const char* name;  // "table"
  unsigned point;
};

// Throws GlError when a storage point is beyond this context's limit, one of
// `view`'s points, or another's of `storage`; or when the uniform point is
// `view`'s or beyond its limit. `type` names the struct ("GlLightBindings").
// Needs a current context.
void validate_lookup_points(const char* type, std::span<const LookupPoint> storage, LookupPoint uniform,
                            const GlBindings& view);

// "#define PREFIX_TABLE 25\n..." for each point (names upper-cased); with
// `overridable`, each inside #ifndef.
std::string lookup_defines(std::string_view prefix, std::span<const LookupPoint> points, bool overridable);

}  // namespace habuffer::gl
