/// @file
/// Per-pixel node lists on the GPU: the head-pointer image (zeroed before
/// every gather), the node pool's entries and links (the node counter is a
/// word of the driver's counters), and the sort pass after the gather, for
/// three techniques that differ in how they take nodes and when they sort:
/// - lists (seed 002): one node per fragment, sorted by the sort pass;
/// - sorted-lists (seed 001's PreSortLF, with early termination and
///   saturation depth): one node per fragment, kept sorted while inserting
///   (no sort pass);
/// - paged-lists (seed 000's paged lists): nodes taken in pages of
///   kPagedListsPageNodes per pixel, sorted by the sort pass.
///
/// A full pool drops and counts (dropped_pool); adaptive sizing grows the
/// pool by the policy's step past grow_at use of the previous frame's
/// request and shrinks it below shrink_at (SPEC 8's rule on nodes); lossless
/// mode regathers into a pool of at least the nodes the gather asked for.
/// `pool_capacity` 0 is the automatic pool (the CLI's `--pool auto`): one
/// page (one node for lists) per pixel at first, a frame that dropped
/// gathered again at once into a pool of the nodes it asked for (whatever
/// max_attempts), and SPEC 8's rule every frame (whatever adaptive).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include <glm/vec2.hpp>

#include "habuffer/techniques/linked_lists/import_node_lists.h"  // GlNodeListKind::import
#include "habuffer/gl/gl_technique.h"

namespace habuffer::gl {

/// How one node-list technique takes nodes and reads back (declared by each
/// technique's GL descriptor).
struct GlNodeListKind {
  Technique technique;         ///< lists, sorted-lists or paged-lists
  std::uint32_t page_nodes;    ///< nodes a pixel takes at a time (1, or the page)
  bool sort_pass;              ///< sorted after the gather (else kept sorted while inserting)
  /// The CPU container of the same technique holding what was read back.
  std::unique_ptr<FragmentBuffer> (*import)(const TechniqueConfig& config, std::span<const std::uint32_t> heads,
                                           std::span<const glm::uvec2> entries, std::span<const std::uint32_t> links,
                                           std::uint64_t requested);
};

/// The kinds of technique lists (sorted after the gather) and sorted-lists
/// (kept sorted while inserting): one node per fragment.
const GlNodeListKind& lists_kind();
const GlNodeListKind& sorted_lists_kind();  ///< (see lists_kind)

/// Per-pixel node lists' container on the GPU (see the file comment).
class GlLinkedLists final : public GlTechnique {
 public:
  /// Throws std::invalid_argument for a bad config (one of another
  /// technique than `kind`'s among them), GlError beyond the context's
  /// limits. `config.pool_capacity` 0: the automatic pool.
  GlLinkedLists(const TechniqueConfig& config, const GlNodeListKind& kind, AtomicMode mode,
                const GlBindings& bindings);
  /// The container of lists or sorted-lists, by config.technique (any other
  /// technique is refused as above).
  GlLinkedLists(const TechniqueConfig& config, AtomicMode mode, const GlBindings& bindings);
  ~GlLinkedLists() override;

  /// The configuration, validated; `pool_capacity` is the current pool (nodes).
  [[nodiscard]] const TechniqueConfig& config() const { return config_; }
  /// Sets the pool for the next frame (a host's own estimate).
  void resize_pool(std::uint64_t nodes);
  /// GlTechnique interface: the pool of wanted.pool_capacity nodes, or the
  /// most the context's storage-buffer limit holds.
  bool fit_automatic_size(const TechniqueConfig& wanted) override;

  /// GlTechnique interface (see gl_technique.h). With adaptive sizing or an
  /// automatic pool, begin_frame resizes the pool from the nodes the
  /// previous gather asked for; before_gather zeroes the head image and
  /// saturation codes; the Sort pass sorts unless sorted on insert; grow
  /// makes the pool at least the nodes the gather asked for (and one step),
  /// false beyond the context's limits; gathered reports and keeps that request.
  void write_params(GlParams& params) const override;
  void bind() const override;
  void begin_frame(FrameReport& report, const GlFrameOptions& options) override;
  void before_gather() override;
  void reset() override {}
  void gathered(std::span<const std::uint32_t> counter_words, FrameReport& report) override;
  bool grow(const FrameReport& report, const GlFrameOptions& options) override;
  /// The automatic pool grows at once, in the frame that dropped.
  [[nodiscard]] bool grows_at_once() const override { return auto_pool_; }
  /// Whether the pool is automatic (pool_capacity 0 given).
  [[nodiscard]] bool automatic_pool() const { return auto_pool_; }
  /// GlTechnique interface: the automatic pool.
  [[nodiscard]] bool sized_automatically() const override { return auto_pool_; }
  [[nodiscard]] std::uint64_t capacity() const override { return config_.pool_capacity; }
  [[nodiscard]] std::uint64_t memory_bytes() const override;
  [[nodiscard]] std::unique_ptr<FragmentBuffer> read_back() const override;

 protected:
  /// resize_screen (gl_technique.h): a new zeroed head image (and
  /// saturation image); the pool scaled by the ratio of the new screen's area
  /// to the old, rounded up (an automatic pool at least a page per pixel;
  /// the pool kept when the scaled one is beyond the limits), its links
  /// made anew; the last frame's node request forgotten.
  void change_screen(Extent screen) override;

 private:
  struct Gpu;
  void allocate_pool(std::uint64_t nodes);
  /// Why a pool of `nodes` cannot be allocated here, or empty.
  [[nodiscard]] std::string pool_limit(std::uint64_t nodes) const;
  /// Nodes of one page per pixel of `screen`: where an automatic pool starts.
  [[nodiscard]] std::uint64_t page_per_pixel(Extent screen) const;

  GlNodeListKind kind_;
  TechniqueConfig config_;
  bool auto_pool_ = false;
  std::uint64_t last_requested_ = 0;
  std::unique_ptr<Gpu> gpu_;
};

}  // namespace habuffer::gl
