#include "habuffer/slot_storage.h"

#include <sys/mman.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>

namespace habuffer {
namespace {
constexpr std::size_t kPopulateLimit = std::size_t{4} << 30;
}  // namespace

template <class Word>
SlotStorage<Word>::SlotStorage(std::uint64_t slots) : slots_(slots) {
  if (slots == 0) return;
  if (slots > (std::uint64_t{1} << 48) / sizeof(Word))
    throw std::length_error("hash table of " + std::to_string(slots) + " slots exceeds the address space");
  mapped_ = static_cast<std::size_t>(slots * sizeof(Word));
  // Tables up to kPopulateLimit are committed up front, so page faults are
  // paid at allocation and not inside (parallel) insertion, where faulting
  // threads contend for the process's memory map; larger ones commit lazily.
  const int populate = mapped_ <= kPopulateLimit ? MAP_POPULATE : MAP_NORESERVE;
  void* p = mmap(nullptr, mapped_, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | populate, -1, 0);
  if (p == MAP_FAILED)
    throw std::runtime_error("cannot map a hash table of " + std::to_string(mapped_) + " bytes: " + std::strerror(errno));
  data_ = static_cast<Word*>(p);
}

template <class Word>
SlotStorage<Word>::~SlotStorage() {
  release();
}

template <class Word>
void SlotStorage<Word>::release() {
  if (data_ != nullptr) munmap(data_, mapped_);
  data_ = nullptr;
  slots_ = 0;
  mapped_ = 0;
}

template <class Word>
SlotStorage<Word>::SlotStorage(SlotStorage&& o) noexcept
    : data_(std::exchange(o.data_, nullptr)), slots_(std::exchange(o.slots_, 0)), mapped_(std::exchange(o.mapped_, 0)) {}

template <class Word>
SlotStorage<Word>& SlotStorage<Word>::operator=(SlotStorage&& o) noexcept {
  if (this != &o) {
    release();
    data_ = std::exchange(o.data_, nullptr);
    slots_ = std::exchange(o.slots_, 0);
    mapped_ = std::exchange(o.mapped_, 0);
  }
  return *this;
}

template <class Word>
std::uint64_t SlotStorage<Word>::count_nonempty() const {
  std::uint64_t n = 0;
  for (std::uint64_t i = 0; i < slots_; ++i) n += data_[i] != 0;
  return n;
}

template <class Word>
std::uint64_t SlotStorage<Word>::clear_and_count() {
  const std::uint64_t n = count_nonempty();
  clear();
  return n;
}

template <class Word>
void SlotStorage<Word>::clear() {
  if (slots_ != 0) std::memset(data_, 0, mapped_);
}

template class SlotStorage<std::uint64_t>;
template class SlotStorage<std::uint32_t>;

}  // namespace habuffer
