// Meshes (glTF 2.0 section 3.7): one pbrkit Mesh per primitive, with morph targets applied
// at the given weights, strips and fans turned into lists, every index checked, non-finite
// data refused or repaired, and missing normals and tangents generated.
#include <cmath>
#include <map>

#include "pbrkit/scene/gltf/loader.h"
#include "pbrkit/scene/mesh_attributes.h"
#include "pbrkit/scene/mesh_closure.h"

namespace pbrkit::gltf {

void Loader::build_primitive(int mesh_index, int prim_index, const std::vector<double>& weights,
                             std::vector<int>& out, DeformingMesh* deform, int skin) {
  const auto& gmesh = model_.meshes[std::size_t(mesh_index)];
  const auto& prim = gmesh.primitives[std::size_t(prim_index)];
  const std::string where = fmt::format("meshes[{}].primitives[{}]", mesh_index, prim_index);
  const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
  if (mode == TINYGLTF_MODE_POINTS || mode == TINYGLTF_MODE_LINE ||
      mode == TINYGLTF_MODE_LINE_LOOP || mode == TINYGLTF_MODE_LINE_STRIP) {
    warning(fmt::format("{}: points/lines (mode {}) are not rendered; skipped", where, mode));
    return;
  }
  if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
      mode != TINYGLTF_MODE_TRIANGLE_FAN)
    error(where + ".mode", fmt::format("invalid primitive mode {}", mode));

  std::map<std::string, int> attributes(prim.attributes.begin(), prim.attributes.end());
  int indices_accessor = prim.indices;
  const auto draco = draco_.find({mesh_index, prim_index});
  if (draco != draco_.end()) {
    for (const auto& [name, acc] : draco->second.first) attributes[name] = acc;
    indices_accessor = draco->second.second;
  }
  const auto pos_it = attributes.find("POSITION");
  if (pos_it == attributes.end()) {
    warning(fmt::format("{}: no POSITION attribute; skipped", where));
    return;
  }
  Mesh mesh;
  mesh.name = gmesh.name.empty() ? fmt::format("mesh{}", mesh_index) : gmesh.name;
  if (gmesh.primitives.size() > 1) mesh.name += fmt::format(".{}", prim_index);
  auto attr_where = [&](const std::string& name) {
    return fmt::format("{}.attributes.{}", where, name);
  };
  auto read_vec = [&](const std::string& name, int comps, auto& dst) {
    const auto it = attributes.find(name);
    if (it == attributes.end()) return;
    const std::vector<float> f = read_floats(it->second, attr_where(name), comps, true);
    using V = typename std::decay_t<decltype(dst)>::value_type;
    dst.resize(f.size() / std::size_t(comps));
    for (std::size_t i = 0; i < dst.size(); ++i) {
      V v(0.0f);
      for (int c = 0; c < comps; ++c) v[c] = f[i * std::size_t(comps) + std::size_t(c)];
      dst[i] = v;
    }
  };
  read_vec("POSITION", 3, mesh.positions);
  const std::size_t n = mesh.positions.size();
  read_vec("NORMAL", 3, mesh.normals);
  read_vec("TANGENT", 4, mesh.tangents);
  read_vec("TEXCOORD_0", 2, mesh.texcoords0);
  read_vec("TEXCOORD_1", 2, mesh.texcoords1);
  if (attributes.count("COLOR_0")) {
    const int acc = attributes["COLOR_0"];
    const AccessorView cv = accessor_view(acc, attr_where("COLOR_0"));
    if (cv.components == 3) {
      std::vector<glm::vec3> rgb;
      read_vec("COLOR_0", 3, rgb);
      for (const auto& c : rgb) mesh.colors0.push_back(glm::vec4(c, 1.0f));
    } else {
      read_vec("COLOR_0", 4, mesh.colors0);
    }
  }
  auto check_count = [&](const char* name, std::size_t count) {
    if (count != 0 && count != n)
      error(attr_where(name), fmt::format("has {} elements but POSITION has {}", count, n));
  };
  check_count("NORMAL", mesh.normals.size());
  check_count("TANGENT", mesh.tangents.size());
  check_count("TEXCOORD_0", mesh.texcoords0.size());
  check_count("TEXCOORD_1", mesh.texcoords1.size());
  check_count("COLOR_0", mesh.colors0.size());

  // A deforming mesh keeps its targets and joints to pose it (scene/pose.h).
  if (deform) read_deformation(prim, attributes, where, n, skin, *deform);  // skins.cpp
  // Morph targets at the given weights (glTF 2.0 section 3.7.2.2).
  for (std::size_t t = 0; t < prim.targets.size() && t < weights.size(); ++t) {
    const float w = float(weights[t]);
    if (w == 0.0f) continue;
    if (!std::isfinite(w))
      error(fmt::format("meshes[{}].weights[{}]", mesh_index, t), "is not finite");
    for (const auto& target : prim.targets[t]) {
      // (no structured binding: clang 14 cannot capture one in the lambda below)
      const std::string& name = target.first;
      const int acc = target.second;
      const std::string tw = fmt::format("{}.targets[{}].{}", where, t, name);
      auto apply = [&](auto& dst, int comps) {
        if (dst.empty()) return;
        const std::vector<float> d = read_floats(acc, tw, comps, true);
        if (d.size() / std::size_t(comps) != dst.size())
          error(tw, fmt::format("has {} elements, expected {}", d.size() / std::size_t(comps),
                                dst.size()));
        for (std::size_t i = 0; i < dst.size(); ++i)
          for (int c = 0; c < comps; ++c)
            dst[i][c] += w * d[i * std::size_t(comps) + std::size_t(c)];
      };
      if (name == "POSITION")
        apply(mesh.positions, 3);
      else if (name == "NORMAL")
        apply(mesh.normals, 3);
      else if (name == "TANGENT")
        apply(mesh.tangents, 3);
    }
  }

  if (indices_accessor >= 0) {
    std::vector<std::uint32_t> idx = read_indices(indices_accessor, where + ".indices");
    for (std::size_t i = 0; i < idx.size(); ++i)
      if (idx[i] >= n)
        error(where + ".indices",
              fmt::format("accessors[{}][{}] = {} is out of range (the primitive has {} vertices)",
                          indices_accessor, i, idx[i], n));
    mesh.indices = std::move(idx);
  } else {
    mesh.indices.resize(n);
    for (std::size_t i = 0; i < n; ++i) mesh.indices[i] = std::uint32_t(i);
  }
  // Strips and fans to lists (glTF 2.0 section 3.7.2.1 gives the vertex order).
  if (mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN) {
    const std::vector<std::uint32_t> src = std::move(mesh.indices);
    mesh.indices.clear();
    for (std::size_t i = 0; i + 2 < src.size(); ++i) {
      if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        // Triangle i is (p_i, p_{i+1+i%2}, p_{i+2-i%2}): keeps the winding consistent.
        const std::size_t odd = i % 2;
        mesh.indices.insert(mesh.indices.end(), {src[i], src[i + 1 + odd], src[i + 2 - odd]});
      } else {
        mesh.indices.insert(mesh.indices.end(), {src[i + 1], src[i + 2], src[0]});
      }
    }
  } else if (mesh.indices.size() % 3 != 0) {
    warning(fmt::format("{}: {} indices is not a multiple of 3; the last {} ignored", where,
                        mesh.indices.size(), mesh.indices.size() % 3));
    mesh.indices.resize(mesh.indices.size() / 3 * 3);
  }
  triangles_ += mesh.indices.size() / 3;
  if (triangles_ > options_.limits.max_triangles)
    error(where, fmt::format("the scene exceeds the limit of {} triangles",
                             options_.limits.max_triangles));

  // Non-finite data: positions are an error; the rest is repaired with a warning.
  for (std::size_t i = 0; i < n; ++i) {
    const glm::vec3& p = mesh.positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      error(attr_where("POSITION"),
            fmt::format("vertex {} is not finite ({}, {}, {})", i, p.x, p.y, p.z));
  }
  auto all_finite = [](const auto& values, int comps) {
    for (const auto& v : values)
      for (int c = 0; c < comps; ++c)
        if (!std::isfinite(v[c])) return false;
    return true;
  };
  auto zero_non_finite = [&](auto& values, int comps, const char* name) {
    if (all_finite(values, comps)) return;
    warning(fmt::format("{}: NaN/Inf values set to 0", attr_where(name)));
    for (auto& v : values)
      for (int c = 0; c < comps; ++c)
        if (!std::isfinite(v[c])) v[c] = 0.0f;
  };
  zero_non_finite(mesh.texcoords0, 2, "TEXCOORD_0");
  zero_non_finite(mesh.texcoords1, 2, "TEXCOORD_1");
  zero_non_finite(mesh.colors0, 4, "COLOR_0");
  bool normals_ok = !mesh.normals.empty() && all_finite(mesh.normals, 3);
  if (!mesh.normals.empty() && !normals_ok)
    warning(
        fmt::format("{}: NaN/Inf normals; flat normals generated instead", attr_where("NORMAL")));
  if (normals_ok)
    for (auto& nrm : mesh.normals) {
      const float len = glm::length(nrm);
      // Renormalise only what is visibly off, so unit normals round-trip bit-exactly.
      if (!(std::fabs(len - 1.0f) < 1e-4f)) nrm = len > 0.0f ? nrm / len : glm::vec3(0, 0, 1);
    }
  if (!mesh.tangents.empty() && !all_finite(mesh.tangents, 4)) {
    warning(fmt::format("{}: NaN/Inf tangents; regenerated", attr_where("TANGENT")));
    mesh.tangents.clear();
  }
  if (!normals_ok) {
    const std::vector<std::uint32_t> corners = mesh.indices;  // vertex of each corner
    mesh.normals.clear();
    mesh.tangents.clear();  // the frame changes with the normals
    generate_flat_normals(mesh);
    if (deform) {
      // One vertex per corner now: the per-vertex deformation follows its corners.
      auto expand = [&](auto& values) {
        if (values.empty()) return;
        const std::size_t per = values.size() / n;
        std::remove_reference_t<decltype(values)> out_values;
        out_values.reserve(corners.size() * per);
        for (const std::uint32_t c : corners)
          for (std::size_t e = 0; e < per; ++e) out_values.push_back(values[c * per + e]);
        values.swap(out_values);
      };
      for (MorphTarget& t : deform->targets) {
        expand(t.positions);
        expand(t.normals);
        t.tangents.clear();  // the generated frame replaces the file's
      }
      expand(deform->joints);
      expand(deform->weights);
      deform->flat_normals = true;
    }
  }

  if (prim.material >= 0) {
    if (std::size_t(prim.material) >= model_.materials.size())
      error(where + ".material", fmt::format("material {} does not exist", prim.material));
    mesh.material = prim.material;
  }
  const Material& mat =
      mesh.material >= 0 ? scene_.materials[std::size_t(mesh.material)] : Scene::default_material();
  ensure_tangents(mesh, mat);  // for the normal maps and anisotropy
  if (deform) {
    deform->mesh = int(scene_.meshes.size());
    deform->positions = mesh.positions;
    deform->normals = mesh.normals;
    deform->tangents = mesh.tangents;
  }
  scene_.meshes.push_back(std::move(mesh));
  out.push_back(int(scene_.meshes.size()) - 1);
}

std::vector<int> Loader::build_mesh(int mesh_index, const std::vector<double>& weights) {
  std::vector<int> out;
  const auto& gmesh = model_.meshes[std::size_t(mesh_index)];
  std::vector<int> gltf_primitive;  // out[i] was built from primitives[gltf_primitive[i]]
  for (std::size_t p = 0; p < gmesh.primitives.size(); ++p) {
    build_primitive(mesh_index, int(p), weights, out);
    gltf_primitive.resize(out.size(), int(p));
  }
  decide_closure(mesh_index, out, gltf_primitive);
  add_variant_materials(mesh_index, out, gltf_primitive);  // variants.cpp
  return out;
}

std::vector<int> Loader::build_deforming_mesh(int mesh_index, int node, int skin) {
  std::vector<int> out;
  const auto& gmesh = model_.meshes[std::size_t(mesh_index)];
  std::vector<int> gltf_primitive;
  for (std::size_t p = 0; p < gmesh.primitives.size(); ++p) {
    DeformingMesh d;
    d.node = node;
    d.skin = skin;
    const std::size_t before = out.size();
    build_primitive(mesh_index, int(p), {}, out, &d, skin);  // at rest: no morph applied
    if (out.size() > before) motion_.deforming.push_back(std::move(d));
    gltf_primitive.resize(out.size(), int(p));
  }
  decide_closure(mesh_index, out, gltf_primitive);
  add_variant_materials(mesh_index, out, gltf_primitive);  // variants.cpp
  return out;
}

void Loader::decide_closure(int mesh_index, const std::vector<int>& primitives,
                            const std::vector<int>& gltf_primitive, const std::string& when) {
  // KHR_materials_volume, "Extending Materials": a thickness above 0 makes "the mesh to
  // which the material is attached" a volume boundary, which "requires a manifold/closed
  // mesh". A glTF mesh may split one shell across primitives (an exporter splits where the
  // UV layout or a vertex limit asks), so a primitive is closed when its own triangles
  // close, or when those of all the primitives of its glTF mesh with the same material
  // close together: one medium, one boundary. Checked only where a volume needs it (the
  // edge count hashes every vertex).
  const auto has_volume = [&](int m) {
    const Material& mat = scene_.material_of(scene_.meshes[std::size_t(m)]);
    return mat.volume && mat.volume->thickness_factor > 0.0f;
  };
  for (std::size_t i = 0; i < primitives.size(); ++i) {
    Mesh& mesh = scene_.meshes[std::size_t(primitives[i])];
    if (!has_volume(primitives[i])) continue;
    const EdgeCount own = count_edges(mesh);
    mesh.closed = own.closed();
    if (mesh.closed) continue;
    std::vector<const Mesh*> shell;
    for (const int other : primitives)
      if (scene_.meshes[std::size_t(other)].material == mesh.material)
        shell.push_back(&scene_.meshes[std::size_t(other)]);
    if (shell.size() > 1) mesh.closed = count_edges(shell).closed();
    if (!mesh.closed)
      warning(fmt::format(
          "meshes[{}].primitives[{}]: the material (materials[{}]) has KHR_materials_volume, but "
          "the primitive is not closed, alone or with the mesh's other primitives of that "
          "material ({} edges not shared by exactly two triangles); it is rendered thin-walled{}",
          mesh_index, gltf_primitive[i], mesh.material, own.unpaired, when));
  }
}

}  // namespace pbrkit::gltf
