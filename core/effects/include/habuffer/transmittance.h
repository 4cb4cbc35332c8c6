/// @file
/// Translucent shadows from a light-view fragment buffer (seed 000, section
/// 6: "A HA-buffer is rendered from the light view and used as a shadow map.
/// Since it contains all fragment colors and opacities ordered by depth,
/// translucent effects may be applied."). A receiving point, mapped to the
/// light's view (LightView), has a light pixel and a depth code; its
/// transmittance T is the product of (1 - alpha) of the light buffer's
/// records at that pixel that lie nearer to the light than the receiver by
/// more than a bias, alpha being each record's 8-bit opacity over 255:
///
///   T = prod over records r of the pixel with code(r) > code + bias of (1 - alpha(r))
///
/// (codes grow toward the light, SPEC 2). The walk is SPEC 7's, nearest
/// first, stopping at the first record that is not nearer: the HA-buffer
/// does it in shared/ha_traverse.glsl's ha_transmittance (the GPU path's
/// code), every technique that stores lists through its list() here, with
/// the same float32 products in the same order, so the two agree bit for bit.
///
/// The bias rule. A surface's own records sit at the receiver's code when
/// the surface faces the light (an orthographic light over planes
/// perpendicular to it: bias 0 excludes them exactly, since "nearer" is
/// strict), and up to the surface's depth slope over one light pixel away
/// when it is slanted; a bias of that many codes excludes them (the default
/// of LightView is derived from it, see light_view.h).
#pragma once

#include <cstdint>
#include <span>

#include "habuffer/fragment_buffer.h"

namespace habuffer {

/// T of one list given nearest first (codes falling), for a receiver at
/// depth code `code` with `bias` codes: see the file comment. Alpha is the
/// data word's low byte (L64 colour records).
float list_transmittance(std::span<const ListEntry> nearest_first, std::uint32_t code, std::uint32_t bias);

/// T at pixel (x, y) of `light`, any technique that stores lists (through
/// list(); the HA-buffer's own HaBuffer::transmittance gives the same value).
/// Throws std::invalid_argument for a technique that stores no lists or L32
/// records (no opacity), std::out_of_range for a pixel off its screen.
float transmittance(const FragmentBuffer& light, std::uint32_t x, std::uint32_t y, std::uint32_t code,
                    std::uint32_t bias);

/// 2x2 percentage-closer filtering: T at the four light pixels whose centres
/// surround window position (wx, wy) (pixels; clamped to the map), weighted
/// bilinearly, the same operations as gl/glsl/shaders/light_lookup.glsl's
/// habuffer_shadow_transmittance_pcf. A surface's own records at the
/// farthest of the four lie up to 1.4 pixels from the receiver (the nearest
/// pixel's centre up to 0.7), so the bias must cover twice the distance:
/// shadow_bias_codes for twice the slope. Throws as transmittance().
float transmittance_pcf(const FragmentBuffer& light, float wx, float wy, std::uint32_t code, std::uint32_t bias);

}  // namespace habuffer
