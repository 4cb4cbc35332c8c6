/// @file
/// Buffer objects as the library uses them: created with their size checked
/// (a failed allocation in a host context would otherwise leave a short buffer
/// that shaders silently read past; the host's errors are not ours to consume
/// with glGetError), zeroed, and read back as 32-bit words.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <vector>

#include "habuffer/extent.h"
#include "habuffer/gl/gl_context.h"

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

/// A buffer object the library allocated and owns (create_buffer's store):
/// deleted with it, movable, never copied, and knowing its size, so a
/// container's memory is the sum of what it allocated rather than a formula
/// kept in step with the allocations by hand. An empty GlStorage (the
/// default) holds no buffer and no bytes: the buffers a configuration does
/// not use (emulated64's locks, the saturation image).
class GlStorage {
 public:
  GlStorage() = default;
  /// create_buffer(bytes, data): throws GlError when OpenGL cannot allocate it.
  explicit GlStorage(std::uint64_t bytes, const void* data = nullptr);
  ~GlStorage();
  GlStorage(GlStorage&& other) noexcept;
  GlStorage& operator=(GlStorage&& other) noexcept;
  GlStorage(const GlStorage&) = delete;
  GlStorage& operator=(const GlStorage&) = delete;

  /// The buffer's name (0 when empty).
  [[nodiscard]] unsigned id() const { return id_; }
  /// Bytes of its store: the size asked for, rounded up to whole words (0 when empty).
  [[nodiscard]] std::uint64_t bytes() const { return bytes_; }
  /// Whether it holds a buffer.
  explicit operator bool() const { return id_ != 0; }
  /// Sets every byte to zero (nothing when empty).
  void zero() const;
  /// Its first `words` 32-bit words.
  [[nodiscard]] std::vector<std::uint32_t> read_words(std::uint64_t words) const;
  /// Its first `count` items of T.
  template <class T>
  [[nodiscard]] std::vector<T> read(std::uint64_t count) const {
    std::vector<T> out(count);
    read_into(out.data(), count * sizeof(T));
    return out;
  }
  /// Binds it at shader-storage point `point` (bind_at; nothing when empty).
  void bind_storage(unsigned point) const;

 private:
  void read_into(void* out, std::uint64_t bytes) const;
  void release();  // deletes the buffer where its context is current (gl_context.h)
  unsigned id_ = 0;
  std::uint64_t bytes_ = 0;
  MadeOn made_on_;
};

/// A 2D texture of one level the library allocated and owns, knowing its
/// size in bytes (the blended baselines' accumulators).
class GlTexture {
 public:
  GlTexture() = default;
  /// glTextureStorage2D of `format` at `size`, `texel_bytes` per texel.
  GlTexture(unsigned format, Extent size, std::uint32_t texel_bytes);
  ~GlTexture();
  GlTexture(GlTexture&& other) noexcept;
  GlTexture& operator=(GlTexture&& other) noexcept;
  GlTexture(const GlTexture&) = delete;
  GlTexture& operator=(const GlTexture&) = delete;

  /// The texture's name (0 when empty).
  [[nodiscard]] unsigned id() const { return id_; }
  /// Bytes of its one level (0 when empty).
  [[nodiscard]] std::uint64_t bytes() const { return bytes_; }

 private:
  void release();  // deletes the texture where its context is current (gl_context.h)
  unsigned id_ = 0;
  std::uint64_t bytes_ = 0;
  MadeOn made_on_;
};

/// The bytes of every object listed: a container's memory_bytes().
template <class... Objects>
[[nodiscard]] std::uint64_t bytes_of(const Objects&... objects) {
  return (std::uint64_t{0} + ... + objects.bytes());
}

}  // namespace habuffer::gl
