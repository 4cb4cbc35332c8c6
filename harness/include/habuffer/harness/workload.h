/// @file
/// What a harness command renders: a scene (by name or mesh file, with its
/// options) or a recorded fragment stream, at one screen size; made once and
/// rendered many times through render_scene / render_fragments with a fixed
/// view (the scene's default camera).
///
/// Scene words for lists on the command line: NAME[:KEY=VALUE]... with keys
/// count, order (front|back), opacity, seed and spread, e.g.
/// "planes:order=front:count=32", each obeying the rule of its `habuffer
/// render` flag (one catalog: habuffer/scene_catalog.h); a key the scene does
/// not take, or given twice, is refused. One key belongs to the workload
/// rather than the scene: samples=S (1, 2, 4 or 8), the samples per pixel it
/// is rasterized with (issue 37: "engine:samples=4" is engine antialiased,
/// every technique run with coverage masks and scored against the
/// per-sample reference). A word ending in .csv is a fragment stream and
/// takes no keys. A file name holding the separators is written with them
/// escaped: "my\:mesh.obj:opacity=0.5", "a\,b.csv" in a comma list
/// (habuffer/list_text.h, the one rule of every list).
#pragma once

#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "habuffer/fragment.h"
#include "habuffer/render/image.h"
#include "habuffer/render/render_job.h"
#include "habuffer/scene.h"
#include "habuffer/scene_catalog.h"

namespace habuffer::harness {

/// One scene word, parsed (see the file comment).
struct WorkloadSpec {
  std::string scene;      ///< name or mesh file; empty for a stream
  std::string fragments;  ///< fragment CSV; empty for a scene
  SceneOptions options;   ///< the word's keys applied to the scene's defaults
  std::string word;       ///< as given
  std::set<std::string> keys;  ///< the option keys the word gave ("count", ...)
  std::uint32_t samples = 1;   ///< samples per pixel (the word's samples=S; 1 by default)
  /// The file the workload reads (a fragment CSV, a mesh file, or the model
  /// a catalog name resolves to), or empty for a procedural scene: the
  /// harness checks it against the outputs.
  [[nodiscard]] std::string input_file() const;
};

/// Parses one scene word. Throws std::invalid_argument naming the word and key.
WorkloadSpec parse_workload_spec(const std::string& word);
/// A fragment file named by an option that takes one (plan --fragments):
/// the whole value is the file, whatever its extension or characters.
WorkloadSpec fragment_workload(const std::string& path);

/// The fragments of a workload's view and their exact composite: what every
/// render is measured against.
struct ExactCapture {
  std::uint64_t fragments = 0;  ///< reaching insertion (after opaque rejection)
  std::vector<std::uint32_t> pixel_fragments;  ///< depth complexity, row-major, row 0 at the bottom
  std::vector<Fragment> stream;                ///< the fragments themselves
  std::vector<glm::vec3> backgrounds;          ///< per pixel: the opaque pass's colour
  Image reference;                             ///< SPEC 7 in double precision, as float
};

/// A scene or stream made once at one screen size and rendered many times (see the file comment).
class Workload {
 public:
  /// Makes the scene or reads the stream (throws SceneError, DataError).
  Workload(const WorkloadSpec& spec, Extent size);

  /// The word as given.
  [[nodiscard]] const std::string& label() const { return spec_.word; }
  /// The word, parsed.
  [[nodiscard]] const WorkloadSpec& spec() const { return spec_; }
  /// The screen, pixels.
  [[nodiscard]] Extent size() const { return size_; }
  /// Whether it is a recorded fragment stream (no scene).
  [[nodiscard]] bool is_stream() const { return !scene_; }
  /// The scene, owned by the workload; nullptr for a stream.
  [[nodiscard]] const Scene* scene() const { return scene_ ? &*scene_ : nullptr; }

  /// s.frames frames of the scene's default view (every frame the same view,
  /// on the buffers the first made) or of the stream (CPU path only: throws
  /// std::invalid_argument for the GL path) with `s`'s technique;
  /// s.config.screen and the camera are set here. Needs a current GL context
  /// for scenes.
  [[nodiscard]] RenderResult render(RenderSettings s) const;
  /// The exact capture (the CPU path's fragments, composited by reference_image).
  [[nodiscard]] ExactCapture capture() const;

 private:
  WorkloadSpec spec_;
  Extent size_;
  std::optional<Scene> scene_;
  std::vector<Fragment> stream_;
};

/// Median, smallest and largest of a sample (spread_of).
struct Spread {
  double median = 0.0, min = 0.0, max = 0.0;  ///< in the sample's unit
};
/// Median (the mean of the middle two for an even count), smallest and largest of `v` (empty: zeros).
Spread spread_of(std::vector<double> v);

}  // namespace habuffer::harness
