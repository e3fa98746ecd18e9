// load(), Scene, Camera, look_at(): a scene is loaded once and rendered many times, as the
// CLI does per process; what Python reads from it is a summary (materials, cameras,
// lights, bounds, counts, animations), not the mesh data. Scene.pose() is its one change:
// it swaps in a posed copy, so that renders already holding the old scene keep it.
#include <pybind11/stl.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>

#include "bindings.h"
#include "interrupt.h"
#include "pbrkit/scene/camera.h"
#include "pbrkit/scene/load.h"
#include "pbrkit/scene/material_schema.h"
#include "pbrkit/scene/pose.h"
#include "pbrkit/scene/scene.h"
#include "pbrkit/util/error.h"
#include "scene_handle.h"

namespace py = pybind11;

namespace pbrkit::python {

namespace {

py::tuple vec3(glm::vec3 v) {
  return py::make_tuple(v.x, v.y, v.z);
}

glm::vec3 to_vec3(const py::handle& obj, const char* name) {
  const auto v = obj.cast<std::vector<float>>();
  if (v.size() != 3 || !std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
    throw py::value_error(std::string(name) + ": expected three finite numbers");
  return {v[0], v[1], v[2]};
}

py::dict material_dict(const Material& m) {
  py::dict d;
  d["name"] = m.name;
  d["base_color"] = py::make_tuple(m.base_color_factor.r, m.base_color_factor.g,
                                   m.base_color_factor.b, m.base_color_factor.a);
  d["metallic"] = m.metallic_factor;
  d["roughness"] = m.roughness_factor;
  d["emissive"] = vec3(m.emissive_factor * m.emissive_strength);
  d["ior"] = m.ior;
  d["double_sided"] = m.double_sided;
  // The surface extensions the material uses (the material schema's, less
  // KHR_materials_emissive_strength, which "emissive" already includes), and each one's
  // factors under its README's property names: a number, or a tuple for a colour.
  py::list ext;
  py::dict values;
  for (const MaterialExtension& x : material_extensions()) {
    if (!x.present(m)) continue;
    ext.append(x.name);
    py::dict factors;
    for (const MaterialFactor& f : x.factors) {
      const float* v = f.read(m);
      factors[f.json_name] =
          f.components == 3 ? py::object(vec3({v[0], v[1], v[2]})) : py::object(py::float_(v[0]));
    }
    values[x.name] = factors;
  }
  d["extensions"] = ext;
  d["extension_factors"] = values;
  return d;
}

py::dict light_dict(const Light& l) {
  py::dict d;
  d["name"] = l.name;
  d["type"] = l.type == Light::Type::kPoint  ? "point"
              : l.type == Light::Type::kSpot ? "spot"
                                             : "directional";
  d["color"] = vec3(l.color);
  d["intensity"] = l.intensity;
  d["range"] = l.range ? py::cast(*l.range) : py::none();
  d["position"] = vec3(l.position);
  d["direction"] = vec3(l.direction);
  if (l.type == Light::Type::kSpot) {
    d["inner_cone_angle"] = l.inner_cone_angle;
    d["outer_cone_angle"] = l.outer_cone_angle;
  }
  return d;
}

py::dict animation_dict(const Animation& a) {
  py::dict d;
  d["name"] = a.name;
  d["start"] = a.start();
  d["end"] = a.end();
  d["channels"] = a.channels.size();
  return d;
}

}  // namespace

PoseTime pose_argument(const Scene& scene, const py::object& animation, double time,
                       const char* animation_arg, const char* time_arg) {
  if (!std::isfinite(time))
    throw py::value_error(std::string(time_arg) + ": expected a finite number of seconds");
  if (animation.is_none()) {
    // As the command line's --animation-time needs --animation: a time of the rest pose
    // would be silently ignored.
    if (time != 0.0)
      throw py::value_error(std::string(time_arg) + ": needs " + animation_arg +
                            " (which animation the time is in)");
    return {};
  }
  // bool is an int to Python; True as "animation 1" would be a surprise.
  if (py::isinstance<py::bool_>(animation) ||
      (!py::isinstance<py::str>(animation) && !py::isinstance<py::int_>(animation)))
    throw py::type_error(std::string(animation_arg) +
                         ": expected None, an animation's name or its index");
  try {
    return {find_animation(scene, py::str(animation).cast<std::string>()), float(time)};
  } catch (const Error& e) {
    throw py::value_error(std::string(animation_arg) + ": " + e.what());
  }
}

void bind_scene(py::module_& m) {
  py::class_<Camera>(m, "Camera",
                     "A camera: one of a scene's glTF cameras (Scene.cameras) or one made with "
                     "look_at(). Renders keep its vertical field of view at any image size.")
      .def_readonly("name", &Camera::name)
      .def_property_readonly("position", [](const Camera& c) { return vec3(c.position()); })
      .def_property_readonly("forward", [](const Camera& c) { return vec3(c.forward()); })
      .def_property_readonly("yfov_degrees",
                             [](const Camera& c) { return c.yfov * 180.0f / 3.14159265358979f; })
      .def_property_readonly("orthographic",
                             [](const Camera& c) { return c.type == Camera::Type::kOrthographic; })
      .def("__repr__", [](const Camera& c) {
        return "<pbrkit.Camera '" + c.name + "' at " + std::string(py::repr(vec3(c.position()))) +
               ">";
      });

  m.def(
      "look_at",
      [](const py::handle& eye, const py::handle& target, const py::handle& up, float fov) {
        const glm::vec3 e = to_vec3(eye, "eye"), t = to_vec3(target, "target"),
                        u = to_vec3(up, "up");
        if (glm::length(t - e) == 0.0f) throw py::value_error("look_at: eye and target coincide");
        if (glm::length(glm::cross(t - e, u)) == 0.0f)
          throw py::value_error("look_at: up is parallel to the view direction");
        if (!(fov > 0.0f && fov < 180.0f))
          throw py::value_error("look_at: fov must be in (0, 180) degrees");
        Camera c;
        c.name = "look_at";
        c.yfov = fov * 3.14159265358979f / 180.0f;
        c.camera_to_world = glm::inverse(glm::lookAt(e, t, u));
        return c;
      },
      py::arg("eye"), py::arg("target"), py::arg("up") = py::make_tuple(0.0f, 1.0f, 0.0f),
      py::arg("fov") = 45.0f,
      "A perspective camera at `eye` looking at `target`, `fov` the vertical field of view in "
      "degrees.");

  py::class_<SceneHandle>(m, "Scene",
                          "A loaded scene (pbrkit.load). A read-only summary (materials, "
                          "cameras, lights, bounds, counts, variants, animations) and one "
                          "change, pose().")
      .def_property_readonly("source", [](const SceneHandle& s) { return s.scene->source; })
      .def_property_readonly(
          "materials",
          [](const SceneHandle& s) {
            py::list l;
            for (const Material& mat : s.scene->materials) l.append(material_dict(mat));
            return l;
          },
          "One dict per material: name, base_color, metallic, roughness, "
          "emissive (the factor times KHR_materials_emissive_strength), ior, "
          "double_sided, extensions (the KHR_materials_* surface extensions "
          "it uses) and extension_factors ({extension: {JSON property name: "
          "a number, or a tuple for a colour}}).")
      .def_property_readonly("cameras", [](const SceneHandle& s) { return s.scene->cameras; })
      .def_property_readonly("lights",
                             [](const SceneHandle& s) {
                               py::list l;
                               for (const Light& light : s.scene->lights)
                                 l.append(light_dict(light));
                               return l;
                             })
      .def_property_readonly("bounds",
                             [](const SceneHandle& s) {
                               const Bounds b = s.scene->world_bounds();
                               return py::make_tuple(vec3(b.min), vec3(b.max));
                             })
      .def_property_readonly("triangle_count",
                             [](const SceneHandle& s) { return s.scene->triangle_count(); })
      .def_property_readonly("mesh_count",
                             [](const SceneHandle& s) { return s.scene->meshes.size(); })
      .def_property_readonly("instance_count",
                             [](const SceneHandle& s) { return s.scene->instances.size(); })
      .def_property_readonly("warnings", [](const SceneHandle& s) { return s.scene->warnings; })
      .def_property_readonly(
          "variants", [](const SceneHandle& s) { return s.scene->variants; },
          "The material variants' names (KHR_materials_variants), in the file's order; "
          "render(variant=) takes a name or an index.")
      .def_property_readonly(
          "animations",
          [](const SceneHandle& s) {
            py::list l;
            if (s.scene->motion)
              for (const Animation& a : s.scene->motion->animations) l.append(animation_dict(a));
            return l;
          },
          "One dict per glTF animation, in the file's order: name, start and end (its first "
          "and last keyframe, seconds) and channels (how many properties it drives); "
          "render(animation=) and pose() take a name or an index.")
      .def(
          "pose",
          [](SceneHandle& s, const py::object& animation, double time) {
            const PoseTime pose = pose_argument(*s.scene, animation, time, "animation", "time");
            // A posed copy replaces the shared scene: a render on another thread keeps the
            // pose it started with. Poses are absolute (from the rest data the loader kept),
            // so posing a posed scene again is the same as posing the loaded one.
            // A pose the file makes not finite is pbrkit.Error, naming the node.
            auto posed = std::make_shared<Scene>(*s.scene);
            pose_scene(*posed, pose);
            s.scene = std::move(posed);
          },
          py::arg("animation") = py::none(), py::arg("time") = 0.0,
          "Poses the scene by `animation` (a name or an index of Scene.animations) at `time` "
          "seconds (clamped to its keys): its instance transforms, skinned and morphed meshes, "
          "cameras and lights, for every later render and for bounds, cameras and lights. "
          "pose() (animation None) is the rest pose again.")
      .def("__repr__", [](const SceneHandle& s) {
        return "<pbrkit.Scene " + s.scene->source + ": " +
               std::to_string(s.scene->triangle_count()) + " triangles, " +
               std::to_string(s.scene->materials.size()) + " materials, " +
               std::to_string(s.scene->lights.size()) + " lights>";
      });

  m.def(
      "_load",
      [](const std::string& path_or_name) {
        SceneHandle handle;
        run_interruptible(
            [&](WorkControl& control) {
              // Ctrl-C stops a long node walk (the partial scene is dropped: the
              // KeyboardInterrupt is raised once the load returns).
              LoadOptions options;
              options.progress = control.callback();
              handle.scene = std::make_shared<const Scene>(load_scene(path_or_name, options));
            },
            py::none());
        return handle;
      },
      py::arg("path_or_builtin_name"));
  m.def("builtin_scenes", &builtin_scene_names, "The names of the built-in scenes.");
}

}  // namespace pbrkit::python
