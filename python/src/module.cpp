// The `pbrkit._pbrkit` extension: numpy in, numpy out. pbrkit/__init__.py is the public
// face (argument defaults, FileNotFoundError, docstrings); this module is its engine.
#include <pybind11/pybind11.h>

#include "bindings.h"
#include "pbrkit/util/error.h"

namespace py = pybind11;

PYBIND11_MODULE(_pbrkit, m) {
  m.doc() = "pbrkit's C++ library (libpbrkit) bound with pybind11; use the `pbrkit` package.";
  // The library's one exception type: bad input or failed I/O, its message naming the file
  // (and JSON path) or the option and the problem.
  py::register_exception<pbrkit::Error>(m, "Error", PyExc_RuntimeError);
  pbrkit::python::bind_scene(m);
  pbrkit::python::bind_render(m);
  pbrkit::python::bind_images(m);
  pbrkit::python::bind_bake(m);
  pbrkit::python::bind_brdf(m);
}
