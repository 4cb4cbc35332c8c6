#include "habuffer/technique.h"

#include <algorithm>
#include <stdexcept>

#include "habuffer/technique_descriptor.h"
#include "habuffer/technique_params.h"

namespace habuffer {

std::string to_string(Technique t) { return std::string(descriptor(t).name); }

std::optional<Technique> parse_technique(std::string_view name) {
  if (const TechniqueDescriptor* d = find_technique(name)) return d->technique;
  return std::nullopt;
}

std::vector<Technique> all_techniques() {
  std::vector<Technique> all;
  for (const TechniqueDescriptor* d : technique_registry()) all.push_back(d->technique);
  return all;
}

bool stores_lists(Technique t) { return descriptor(t).stores_lists; }
bool exact_technique(Technique t) { return descriptor(t).exact; }
bool uses_pool(Technique t) { return descriptor(t).capacity == CapacityKind::PoolNodes; }
bool uses_layers(Technique t) { return descriptor(t).capacity == CapacityKind::PixelLayers; }
bool uses_table(Technique t) { return descriptor(t).capacity == CapacityKind::TableSlots; }

std::string technique_names() {
  std::string s;
  for (Technique t : all_techniques()) s += (s.empty() ? "" : ", ") + to_string(t);
  return s;
}

void TechniqueConfig::validate() const {
  const TechniqueDescriptor& d = descriptor(technique);
  buffer.validate();
  if (!d.early_cull && buffer.early_cull_tau > 0.0f)
    throw std::invalid_argument("early cull applies to " + techniques_taking("early-cull") + ": technique " +
                                to_string(technique) + " has none");
  if (buffer.samples > 1 && !d.stores_lists)
    throw std::invalid_argument("samples " + std::to_string(buffer.samples) + " per pixel need a technique that stores "
                                "lists (a coverage mask per record): " + to_string(technique) + " stores none");
  if (occupancy && !d.takes("occupancy"))
    throw std::invalid_argument("occupancy maps apply to " + techniques_taking("occupancy") + ", not " +
                                to_string(technique));
  if (occupancy_words == 0 || occupancy_words > HABUFFER_MAX_OCCUPANCY_WORDS)
    throw std::invalid_argument("occupancy words " + std::to_string(occupancy_words) + " outside [1, " +
                                std::to_string(HABUFFER_MAX_OCCUPANCY_WORDS) + "]");
  if (!(depth_range.near_t >= 0.0f && depth_range.near_t < depth_range.far_t && depth_range.far_t <= 1.0f))
    throw std::invalid_argument("depth range [" + std::to_string(depth_range.near_t) + ", " +
                                std::to_string(depth_range.far_t) + "] is not an interval within [0, 1]");
  d.validate(*this);
}

void validate_pool(const TechniqueConfig& c) {
  // Links are 32-bit node numbers with 0 for "none".
  if (c.pool_capacity == 0 || c.pool_capacity >= UINT32_MAX)
    throw std::invalid_argument("node pool of " + std::to_string(c.pool_capacity) +
                                " nodes: must be in [1, 2^32 - 2] (0, automatic, is for build_technique and the GL "
                                "containers, which size it)");
}

TechniqueConfig grown_pool(const TechniqueConfig& c, const ResizePolicy& policy, const GrowthNeed& need) {
  TechniqueConfig next = c;
  next.pool_capacity = policy.grown(c.pool_capacity, need.nodes_requested);
  return next;
}

void validate_layers(const TechniqueConfig& c) {
  if (c.layers == 0) throw std::invalid_argument(to_string(c.technique) + " needs at least 1 layer per pixel");
  if (std::uint64_t{c.layers} * c.buffer.screen.area() > UINT32_MAX)
    throw std::invalid_argument(std::to_string(c.layers) + " layers of screen " + c.buffer.screen.str() +
                                " exceed 2^32 - 1 slots");
}

std::string TechniqueConfig::limit() const {
  try {
    validate();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

std::uint64_t GrowthNeed::count_for(Technique t) const { return uses_pool(t) ? nodes_requested : records; }

TechniqueConfig TechniqueConfig::grown(const ResizePolicy& policy, const GrowthNeed& need) const {
  return descriptor(technique).grown(*this, policy, need);
}

TechniqueConfig TechniqueConfig::sized_for(const ResizePolicy& policy, std::uint64_t fragments) const {
  TechniqueConfig c = *this;
  if (uses_table(technique)) c.buffer.table = policy.initial_table(buffer.screen, fragments);
  if (uses_pool(technique)) c.pool_capacity = policy.automatic(fragments);
  return c;
}

TechniqueConfig TechniqueConfig::relevant() const {
  const TechniqueDescriptor& d = descriptor(technique);
  const TechniqueConfig defaults;
  TechniqueConfig c = *this;
  if (d.capacity != CapacityKind::PoolNodes) c.pool_capacity = defaults.pool_capacity;
  if (d.capacity != CapacityKind::PixelLayers) c.layers = defaults.layers;
  if (!d.takes("occupancy")) c.occupancy = defaults.occupancy;
  if (!c.occupancy) c.occupancy_words = defaults.occupancy_words;
  if (!d.reads_depth_range) c.depth_range = defaults.depth_range;
  return c;
}

std::uint64_t TechniqueConfig::configured_capacity() const {
  switch (descriptor(technique).capacity) {
    case CapacityKind::TableSlots: return buffer.table_or_screen().area();
    case CapacityKind::PoolNodes: return pool_capacity;
    case CapacityKind::PixelLayers: return std::uint64_t{layers} * buffer.screen.area();
    case CapacityKind::None: break;
  }
  return 0;
}

TechniqueConfig ha_technique_config(const BufferConfig& buffer) {
  TechniqueConfig c;
  c.technique = Technique::Ha;
  c.buffer = buffer;
  return c;
}

TechniqueConfig validated_as(TechniqueConfig config, Technique t) {
  if (config.technique != t)
    throw std::invalid_argument("technique " + to_string(t) + "'s container refuses a configuration of technique " +
                                to_string(config.technique));
  config.validate();
  return config;
}

void occupancy_geometry(const TechniqueConfig& c, std::uint32_t& near_code, std::uint32_t& bucket_codes) {
  const RecordLayout layout = c.buffer.record_layout();
  near_code = layout.depth_code(c.depth_range.near_t);
  const std::uint32_t far_code = layout.depth_code(c.depth_range.far_t);
  const std::uint64_t span = std::uint64_t{near_code} - far_code + 1;
  const std::uint64_t buckets = std::uint64_t{32} * c.occupancy_words;
  bucket_codes = static_cast<std::uint32_t>((span + buckets - 1) / buckets);
}

}  // namespace habuffer

namespace habuffer {

void write_technique_params(const TechniqueConfig& c, ParamBlock& p) {
  p.habuffer_age_bits = c.buffer.age_bits;
  p.habuffer_coverage_bits = c.buffer.record_layout().coverage_bits();
  p.ll_pool_capacity = static_cast<std::uint32_t>(c.pool_capacity);
  p.habuffer_layers = c.layers;
  p.habuffer_iter_limit = c.buffer.iter_limit;
  p.habuffer_cull_tau = c.buffer.early_cull_tau;
  p.habuffer_saturation = c.buffer.saturation ? 1u : 0u;
  p.kb_occupancy_culling = c.occupancy ? 1u : 0u;
  p.kb_occupancy_words = c.occupancy_words;
  occupancy_geometry(c, p.kb_occupancy_near_code, p.kb_occupancy_bucket_codes);
  p.habuffer_depth_near = c.depth_range.near_t;
  p.habuffer_depth_far = c.depth_range.far_t;
}

KernelUniforms kernel_uniforms(const TechniqueConfig& c) {
  KernelUniforms u;
  write_technique_params(c, u);
  u.habuffer_screen_size = glm::uvec2(c.buffer.screen.x, c.buffer.screen.y);
  u.ha_payload_bits = c.buffer.layout == Layout::L64 ? 32u : 0u;
  return u;
}

}  // namespace habuffer
