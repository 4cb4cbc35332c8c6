// A technique's configuration from Python arguments: the technique's name,
// the screen, the HA-buffer's table, the layout, and the technique options
// as keyword arguments named after the option table's flags (--occupancy-words
// is occupancy_words), read by the table's own parser, so Python takes the
// same values, ranges and refusals as the command line.
#pragma once

#include <pybind11/pybind11.h>

#include <string>

#include "habuffer/lossless_build.h"
#include "habuffer/render/render_job.h"
#include "habuffer/spatial/spatial_hash.h"
#include "habuffer/technique.h"

namespace habuffer::python {

namespace py = pybind11;

/// The Python-side arguments of every container and build.
struct ConfigArgs {
  std::string technique = "ha";
  py::object screen, table = py::none(), layout = py::int_(64);
  std::string offsets = "random";  ///< random or farthest (the HA-buffer's)
  std::uint64_t seed = 1;
  py::object offset_list = py::none();  ///< (n, 2) uint32 rows, instead of a generator
};

/// The validated configuration; ValueError naming the argument otherwise.
TechniqueConfig technique_config_from(const ConfigArgs& a, const py::kwargs& options);
/// (X, Y) or (X, Y, Z) sides in [1, 2^32 - 1] as a spatial hash's domain;
/// TypeError or ValueError naming `domain` otherwise.
spatial::Domain domain_arg(py::handle obj);
/// The path named `path=` ("cpu", "gl", and "vk" where the module has the
/// Vulkan path): every function's one rule; ValueError naming the others.
RenderPath path_arg(const std::string& path);
/// The generator named `name` ("random", "farthest"); ValueError otherwise.
OffsetGenerator offsets_arg(const std::string& name);
/// The offsets the configuration's HA-buffer takes.
OffsetSource offset_source_from(const ConfigArgs& a);
/// The configuration as a dict: technique, screen, table, layout, and the
/// options its technique takes (option-table names, underscores).
py::dict config_dict(const TechniqueConfig& c);
/// --occupancy-words as occupancy_words.
std::string python_name(std::string_view flag);

}  // namespace habuffer::python
