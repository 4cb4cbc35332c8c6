/// @file
/// Buffer objects as the library uses them: created with their size checked
/// (a failed allocation in a host context would otherwise leave a short buffer
/// that shaders silently read past; the host's errors are not ours to consume
/// with glGetError), zeroed, and read back as 32-bit words.
#pragma once

#include <cstdint>
#include <vector>

namespace habuffer::gl {

/// An immutable store of `bytes` (rounded up to whole 32-bit words) in device
/// memory, holding `data` or zeros. Throws GlError naming the size when
/// OpenGL cannot allocate it.
unsigned create_buffer(std::uint64_t bytes, const void* data = nullptr);
/// Sets every byte of `buffer` to zero.
void zero_buffer(unsigned buffer);
/// Binds `buffer` at indexed `point` of `target` (glBindBuffersBase, which,
/// unlike glBindBufferBase, leaves the target's generic binding, the host's, as it is).
void bind_at(unsigned target, unsigned point, unsigned buffer);
/// Deletes the buffer (if any) and sets the name to 0.
void delete_buffer(unsigned& buffer);
/// Reads the first `words` 32-bit words of `buffer` back.
std::vector<std::uint32_t> read_words(unsigned buffer, std::uint64_t words);

}  // namespace habuffer::gl
