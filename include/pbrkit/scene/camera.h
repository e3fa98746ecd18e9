#pragma once
// Camera conventions shared by the path tracer and the OpenGL renderer, so both produce
// the same image of a scene: glTF cameras (local -Z forward, +Y up), the GL projection
// matrices, primary-ray generation, and automatic framing when a file has no camera.
#include <optional>

#include <glm/glm.hpp>

#include "pbrkit/scene/scene.h"

namespace pbrkit {

struct Ray {
  glm::vec3 origin;
  glm::vec3 direction;  ///< unit length
};

/// The automatic camera for a scene without one: perspective, yfov = 45 degrees (0.7854),
/// looking at the centre of the world bounding box from the +Z side, raised 20 degrees
/// above the horizon (direction from target to eye: (0, sin 20, cos 20)), at the distance
/// where the bounding sphere just fits the smaller of the two fields of view.
Camera auto_camera(const Bounds& bounds, float aspect);

/// `index` given: that glTF camera (Error if out of range, naming the count). Otherwise
/// the scene's first camera, or auto_camera when it has none.
Camera select_camera(const Scene& scene, std::optional<int> index, float aspect);

/// An image's size in pixels.
struct ImageSize {
  int width = 512;
  int height = 512;
  float aspect() const { return float(width) / float(height); }
};

/// The aspect ratio (width / height) a camera was authored for: glTF's `aspectRatio` for
/// a perspective camera (none when absent), xmag / ymag for an orthographic one.
std::optional<float> authored_aspect(const Camera& camera);

/// The image size for a render through `camera`: the given width and height; one of them
/// with the other from the camera's authored aspect; neither: `longer_side` pixels along
/// the longer side at the authored aspect (square when the camera has none).
ImageSize image_size(const Camera& camera, std::optional<int> width, std::optional<int> height,
                     int longer_side = 512);

/// A camera and the size of the image to render through it.
struct RenderView {
  Camera camera;
  ImageSize size;
};

/// select_camera and image_size together: the glTF camera (`camera_index`, or the first)
/// sized by image_size; for a scene without cameras, the size first (square unless given)
/// and then the automatic camera for that aspect.
RenderView select_view(const Scene& scene, std::optional<int> camera_index,
                       std::optional<int> width, std::optional<int> height);

/// Half extents of the image plane at unit distance (perspective) or in world units
/// (orthographic), x right, y up, for an image of aspect `aspect` (width / height). The
/// camera's vertical extent (yfov, ymag) is kept and the horizontal one is aspect times
/// it, whatever the camera's authored aspect: a render at any size is never stretched.
glm::vec2 image_plane_half_extent(const Camera& camera, float aspect);

/// World-to-camera matrix (inverse of camera_to_world).
glm::mat4 view_matrix(const Camera& camera);
/// OpenGL clip-space projection per the glTF spec's projection formulas (infinite
/// perspective when zfar is absent), with the image's `aspect` in place of the camera's
/// aspectRatio/xmag (image_plane_half_extent).
glm::mat4 projection_matrix(const Camera& camera, float aspect);

/// Primary ray through `ndc` in [-1,1]^2 (x right, y up; pixel centres at
/// ((x + 0.5) / w * 2 - 1, 1 - (y + 0.5) / h * 2)). Same geometry as projection_matrix.
Ray generate_ray(const Camera& camera, float aspect, glm::vec2 ndc);

}  // namespace pbrkit
