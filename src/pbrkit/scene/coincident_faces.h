#pragma once
// Transmissive faces lying on another object's faces: a glass modelled standing in a
// table's plane, a liquid whose surface is its glass's inner wall. Where two faces share a
// plane and an area, which of the two a ray meets first is decided by the last bit of the
// intersection test (Embree's AVX2 and AVX-512 kernels decide differently), so what a path
// tracer renders there is arbitrary: a path may be shaded as the table while it is still
// inside the glass. Opaque faces may touch freely (no path reaches the face between them).
#include <cstddef>
#include <string>
#include <vector>

#include "pbrkit/scene/scene.h"

namespace pbrkit {

struct CoincidentFaces {
  std::size_t transmissive = 0;  ///< instance (Scene::instances) with a transmissive material
  std::size_t other = 0;         ///< the instance whose faces it lies on
  std::size_t triangles = 0;     ///< the transmissive instance's triangles that do
};

struct CoincidentFacesResult {
  std::vector<CoincidentFaces> pairs;
  /// The search stopped at its work bound (a scene of very many transmissive instances or
  /// triangles near them): `pairs` holds what was found until then.
  bool incomplete = false;
  std::size_t transmissive = 0;  ///< transmissive instances in the scene
  std::size_t checked = 0;       ///< of them, those compared with all their neighbours
};

/// Pairs of instances, one of them transmissive (KHR_materials_transmission,
/// diffuse_transmission or volume), whose faces share a plane (within 1e-6 of the
/// transmissive instance's size) and an area. Each transmissive instance is compared only
/// with the instances near it (a sweep over the instances' bounds), so a scene of many
/// instances costs about what its neighbourhoods hold. The work is bounded:
/// `max_comparisons` instance-bounds and triangle tests, each a few tens of nanoseconds.
CoincidentFacesResult find_coincident_faces(const Scene& scene,
                                            std::size_t max_comparisons = 50'000'000);

/// The warnings load_scene adds for them (and logs after the file's name): one per pair
/// (the first few), naming both nodes.
std::vector<std::string> coincident_face_warnings(const Scene& scene,
                                                  const CoincidentFacesResult& result);

}  // namespace pbrkit
