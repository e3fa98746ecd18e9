// The BRDF's building blocks on numpy arrays, for plotting: the same functions the
// renderers evaluate (core/microfacet.h, core/energy.h), broadcast over their arguments.
#include <pybind11/numpy.h>

#include <cmath>

#include "bindings.h"
#include "pbrkit/core/brdf.h"
#include "pbrkit/core/energy.h"
#include "pbrkit/core/microfacet.h"

namespace py = pybind11;

namespace pbrkit::python {

namespace {

GeometryModel geometry_model(const std::string& model) {
  if (model == "reference") return GeometryModel::kReference;
  if (model == "classic") return GeometryModel::kClassicDirect;
  if (model == "classic-ibl") return GeometryModel::kClassicIBL;
  throw py::value_error("model must be 'reference', 'classic' or 'classic-ibl', got '" + model +
                        "'");
}

// Directions in the x-z plane at the given cosines, on opposite sides of the normal (z).
glm::vec3 at_cosine(float c, float side) {
  const float cc = std::clamp(c, 0.0f, 1.0f);
  return {side * std::sqrt(std::max(0.0f, 1.0f - cc * cc)), 0.0f, cc};
}

}  // namespace

void bind_brdf(py::module_& m) {
  m.def("D", py::vectorize([](float n_dot_h, float roughness) {
          return DistributionGGX(n_dot_h, roughness * roughness);
        }),
        py::arg("n_dot_h"), py::arg("roughness"),
        "GGX normal distribution D(n.h) with alpha = roughness^2 (Walter et al. 2007; the "
        "renderers' DistributionGGX).");
  m.def(
      "G",
      [](py::array_t<float> n_dot_v, py::array_t<float> n_dot_l, py::array_t<float> roughness,
         const std::string& model) {
        const GeometryModel g = geometry_model(model);
        return py::vectorize([g](float nv, float nl, float r) {
          return GeometryG(g, at_cosine(nv, 1.0f), at_cosine(nl, -1.0f), r);
        })(n_dot_v, n_dot_l, roughness);
      },
      py::arg("n_dot_v"), py::arg("n_dot_l"), py::arg("roughness"), py::arg("model") = "reference",
      "Smith masking-shadowing G(n.v, n.l): 'reference' height-correlated (Heitz 2014), "
      "'classic' Schlick-GGX with k = (r+1)^2/8, 'classic-ibl' with k = r^2/2.");
  m.def("F", py::vectorize([](float cos_theta, float f0) {
          return fresnelSchlick(cos_theta, glm::vec3(f0)).x;
        }),
        py::arg("cos_theta"), py::arg("f0"), "Schlick's Fresnel F0 + (1 - F0)(1 - cos)^5.");
  m.def(
      "albedo",
      [](py::array_t<float> mu, py::array_t<float> roughness, const std::string& model) {
        const EnergyTable& table = EnergyTable::get(geometry_model(model));
        return py::vectorize([&table](float u, float r) {
          return table.E(std::clamp(u, 0.0f, 1.0f), std::clamp(r, 0.0f, 1.0f));
        })(mu, roughness);
      },
      py::arg("mu"), py::arg("roughness"), py::arg("model") = "reference",
      "Directional albedo E(mu) of the single-scattering GGX lobe with F = 1 (the energy "
      "table the renderers' multiple-scattering compensation uses).");
}

}  // namespace pbrkit::python
