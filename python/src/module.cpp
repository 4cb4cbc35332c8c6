// The extension module habuffer._habuffer; python/habuffer/__init__.py
// re-exports it. The library's exceptions become Python ones with the
// library's messages: std::invalid_argument ValueError, std::out_of_range
// IndexError (pybind11's own mapping), and the library's own classes below.
#include "bindings.h"
#include "habuffer/csv.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/scene.h"

namespace habuffer::python {

void bind_errors(py::module_& m) {
  py::register_exception<DataError>(m, "DataError", PyExc_RuntimeError);
  py::register_exception<SceneError>(m, "SceneError", PyExc_RuntimeError);
  py::register_exception<gl::GlError>(m, "GlError", PyExc_RuntimeError);
}

}  // namespace habuffer::python

PYBIND11_MODULE(_habuffer, m) {
  using namespace habuffer::python;
  m.doc() = "habuffer: the coherent Robin Hood hash of per-pixel fragment lists (the HA-buffer), its peer techniques, "
            "statistics, harness and spatial hash";
  m.attr("__version__") = HABUFFER_VERSION;
  bind_errors(m);
  bind_config(m);
  bind_buffers(m);
  bind_results(m);
  bind_spatial(m);
  bind_applications(m);
  bind_gl_context(m);
}
