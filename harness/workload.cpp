#include "habuffer/harness/workload.h"

#include <algorithm>
#include <set>
#include <sstream>
#include <stdexcept>

#include "habuffer/interchange.h"
#include "habuffer/list_text.h"
#include "habuffer/number_text.h"
#include "habuffer/record_layout.h"

namespace habuffer::harness {
namespace {

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

}  // namespace

WorkloadSpec fragment_workload(const std::string& path) {
  if (path.empty()) throw std::invalid_argument("an empty fragment file name");
  WorkloadSpec w;
  w.word = path;
  w.fragments = path;
  return w;
}

WorkloadSpec parse_workload_spec(const std::string& word) {
  WorkloadSpec w;
  w.word = word;
  const auto refuse = [&](const std::string& why) { throw std::invalid_argument("scene '" + word + "': " + why); };
  // The word's parts at each unescaped ':' (habuffer/list_text.h: a file
  // named "a:b.obj" is "a\:b.obj").
  const std::vector<std::string> parts = split_list(word, ':');
  w.scene = parts.front();
  if (w.scene.empty()) refuse("no scene name");
  if (ends_with(w.scene, ".csv")) {
    if (parts.size() > 1) refuse("a fragment file takes no options (they are the scenes')");
    w.fragments = w.scene;
    w.scene.clear();
    return w;
  }
  for (std::size_t i = 1; i < parts.size(); ++i) {
    const std::string& part = parts[i];
    if (part.empty()) refuse("empty option after ':'");
    const std::size_t eq = part.find('=');
    if (eq == std::string::npos) refuse("'" + part + "' is not KEY=VALUE");
    const std::string key = part.substr(0, eq), value = part.substr(eq + 1);
    if (!w.keys.insert(key).second) refuse(key + " given twice");
    try {
      if (key == "samples") {
        const std::uint64_t n = parse_unsigned(value, 1, RecordLayout::kMaxSamples);
        if (!RecordLayout::samples_valid(static_cast<std::uint32_t>(n))) throw std::invalid_argument("not 1, 2, 4 or 8");
        w.samples = static_cast<std::uint32_t>(n);
        continue;
      }
      if (!scene_takes(w.scene, key)) refuse("scene " + w.scene + " does not take " + key + " (" + scenes_taking_text(key) + ")");
      set_scene_option(w.options, key, value);
    } catch (const std::invalid_argument& e) {
      if (std::string_view(e.what()).rfind("scene '", 0) == 0) throw;
      refuse(key + "=" + value + ": " + e.what());
    }
  }
  return w;
}

std::string WorkloadSpec::input_file() const {
  if (!fragments.empty()) return fragments;
  return scene_input_file(scene);
}

Workload::Workload(const WorkloadSpec& spec, Extent size) : spec_(spec), size_(size) {
  if (!spec.fragments.empty())
    stream_ = read_fragments(spec.fragments, size);
  else
    scene_ = make_scene(spec.scene, spec.options);
}

RenderResult Workload::render(RenderSettings s) const {
  s.config.screen = size_;
  s.config.samples = spec_.samples;
  s.orbit = false;  // one fixed view: every frame the same (warm-up frames, then timed ones)
  if (!scene_) {
    if (s.path != RenderPath::Cpu) throw std::invalid_argument("fragment stream '" + spec_.word + "' renders on the CPU path only");
    return render_fragments(stream_, s);
  }
  s.camera = {scene_->default_yaw, scene_->default_pitch, s.camera.fov};
  return render_scene(*scene_, s);
}

ExactCapture Workload::capture() const {
  RenderSettings s;
  s.path = RenderPath::Cpu;
  // The CPU path keeps the captured fragments whatever the technique: the
  // cheapest one (unsorted blending, one pass, nothing to grow or regather;
  // multisampled, unsorted lists, the cheapest that keeps masks) gives them,
  // their count and the backgrounds.
  s.technique = spec_.samples > 1 ? Technique::Lists : Technique::Blend;
  s.keep_fragments = true;
  RenderResult r = render(s);
  ExactCapture c;
  c.fragments = r.frames.back().counters.fragments;
  c.pixel_fragments = std::move(r.pixel_fragments);
  c.stream = std::move(r.fragments);
  c.backgrounds = std::move(r.backgrounds);
  c.reference = reference_image(c.stream, size_, c.backgrounds, spec_.samples);
  return c;
}

Spread spread_of(std::vector<double> v) {
  if (v.empty()) return {};
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  const double median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  return {median, v.front(), v.back()};
}

}  // namespace habuffer::harness
