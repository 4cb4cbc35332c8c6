#include "habuffer/harness/workload.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "habuffer/interchange.h"

namespace habuffer::harness {
namespace {

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

template <class T>
T parse_number(const std::string& word, const std::string& key, const std::string& text) {
  T v{};
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size())
    throw std::invalid_argument("scene '" + word + "': " + key + "=" + text + " is not a number");
  return v;
}

}  // namespace

WorkloadSpec parse_workload_spec(const std::string& word) {
  WorkloadSpec w;
  w.word = word;
  if (ends_with(word, ".csv")) {
    w.fragments = word;
    return w;
  }
  std::istringstream in(word);
  std::string part;
  std::getline(in, w.scene, ':');
  if (w.scene.empty()) throw std::invalid_argument("scene '" + word + "': no scene name");
  while (std::getline(in, part, ':')) {
    const std::size_t eq = part.find('=');
    if (eq == std::string::npos) throw std::invalid_argument("scene '" + word + "': '" + part + "' is not KEY=VALUE");
    const std::string key = part.substr(0, eq), value = part.substr(eq + 1);
    if (key == "count") {
      w.options.count = parse_number<std::uint32_t>(word, key, value);
    } else if (key == "seed") {
      w.options.seed = parse_number<std::uint64_t>(word, key, value);
    } else if (key == "opacity") {
      w.options.opacity = parse_number<float>(word, key, value);
    } else if (key == "spread") {
      w.options.spread = parse_number<float>(word, key, value);
    } else if (key == "order") {
      if (value != "front" && value != "back")
        throw std::invalid_argument("scene '" + word + "': order=" + value + " is not front or back");
      w.options.order = value == "front" ? PlaneOrder::FrontToBack : PlaneOrder::BackToFront;
    } else {
      throw std::invalid_argument("scene '" + word + "': unknown key '" + key + "' (count, order, opacity, seed, spread)");
    }
  }
  return w;
}

Workload::Workload(const WorkloadSpec& spec, Extent size) : spec_(spec), size_(size) {
  if (!spec.fragments.empty())
    stream_ = read_fragments(spec.fragments, size);
  else
    scene_ = make_scene(spec.scene, spec.options);
}

RenderResult Workload::render(RenderSettings s) const {
  s.config.screen = size_;
  s.frames = 1;
  if (!scene_) {
    if (s.path == RenderPath::Gl) throw std::invalid_argument("fragment stream '" + spec_.word + "' renders on the CPU path only");
    return render_fragments(stream_, s);
  }
  s.camera = {scene_->default_yaw, scene_->default_pitch, s.camera.fov};
  return render_scene(*scene_, s);
}

ExactCapture Workload::capture() const {
  RenderSettings s;
  s.path = RenderPath::Cpu;
  // The CPU path keeps the captured fragments whatever the technique: the
  // cheapest one (unsorted blending, one pass, nothing to grow or regather)
  // gives them, their count and the backgrounds.
  s.technique = Technique::Blend;
  s.keep_fragments = true;
  RenderResult r = render(s);
  ExactCapture c;
  c.fragments = r.frames.back().counters.fragments;
  c.pixel_fragments = std::move(r.pixel_fragments);
  c.stream = std::move(r.fragments);
  c.backgrounds = std::move(r.backgrounds);
  c.reference = reference_image(c.stream, size_, c.backgrounds);
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
