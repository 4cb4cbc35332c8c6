#include "habuffer/fragment_buffer.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "habuffer/build_report.h"
#include "habuffer/parallel.h"

namespace habuffer {

void check_on_screen(std::span<const Fragment> fragments, Extent screen) {
  for (std::size_t i = 0; i < fragments.size(); ++i) {
    const Fragment& f = fragments[i];
    if (f.x >= screen.x || f.y >= screen.y)
      throw std::out_of_range("fragment " + std::to_string(i) + " at pixel (" + std::to_string(f.x) + "," +
                              std::to_string(f.y) + ") lies outside screen " + screen.str());
  }
}

std::string to_string(InsertOrder order) {
  switch (order) {
    case InsertOrder::Auto: return "auto";
    case InsertOrder::Arrival: return "arrival";
    case InsertOrder::Pixel: return "pixel";
  }
  return "?";
}

std::optional<InsertOrder> parse_insert_order(std::string_view name) {
  for (InsertOrder o : {InsertOrder::Auto, InsertOrder::Arrival, InsertOrder::Pixel})
    if (name == to_string(o)) return o;
  return std::nullopt;
}

bool insert_order_needs_coverage(const InsertOptions& options, std::uint64_t fragments, Extent screen) {
  return options.order == InsertOrder::Auto && options.mode != InsertMode::OwnerComputes &&
         fragments >= kPixelOrderMinFragments && fragments * kPixelOrderPixelsPerFragment >= screen.area();
}

InsertOrder choose_insert_order(const InsertOptions& options, std::uint64_t fragments, std::uint64_t covered_pixels,
                                Extent screen) {
  if (options.order != InsertOrder::Auto) return options.order;
  if (!insert_order_needs_coverage(options, fragments, screen) || covered_pixels == 0) return InsertOrder::Arrival;
  const double depth = static_cast<double>(fragments) / static_cast<double>(covered_pixels);
  return depth >= kPixelOrderMinDepth ? InsertOrder::Pixel : InsertOrder::Arrival;
}

std::optional<InsertMode> parse_insert_mode(std::string_view name) {
  if (name == "auto") return InsertMode::Auto;
  if (name == "serial") return InsertMode::Serial;
  if (name == "atomic") return InsertMode::Atomic;
  if (name == "owner") return InsertMode::OwnerComputes;
  return std::nullopt;
}

void check_pixel(std::uint32_t x, std::uint32_t y, Extent screen) {
  if (x >= screen.x || y >= screen.y)
    throw std::out_of_range("pixel (" + std::to_string(x) + "," + std::to_string(y) + ") lies outside screen " +
                            screen.str());
}

void FragmentBuffer::measure(BuildReport& r) const {
  r.stored = count_stored();
  r.load_factor = r.capacity > 0 ? static_cast<double>(r.stored) / static_cast<double>(r.capacity) : 0.0;
}

std::string FragmentBuffer::capacity_text() const { return std::to_string(capacity()) + " records"; }

}  // namespace habuffer
