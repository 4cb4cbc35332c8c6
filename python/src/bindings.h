// The Python module's parts: each binds one area of the library, and
// module.cpp calls them in order. Shared conversions live in arrays.h.
#pragma once

#include <pybind11/pybind11.h>

namespace habuffer::python {

namespace py = pybind11;

void bind_errors(py::module_& m);      // module.cpp: the library's exceptions as Python ones
void bind_config(py::module_& m);      // config.cpp: techniques, offsets, fragment files
void bind_buffers(py::module_& m);     // buffers.cpp: every technique's container
void bind_results(py::module_& m);     // results.cpp: statistics and harness tables
void bind_spatial(py::module_& m);     // spatial.cpp: the spatial hash
void bind_applications(py::module_& m);  // applications.cpp: solid voxelization
void bind_gl_context(py::module_& m);  // gl_context.cpp: the headless context the GL calls share

}  // namespace habuffer::python
