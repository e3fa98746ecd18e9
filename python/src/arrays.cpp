#include "arrays.h"

#include <cmath>
#include <cstring>
#include <vector>

namespace py = pybind11;

namespace pbrkit::python {

Image image_from_array(const py::handle& obj, const std::string& name,
                       const ArrayRequirements& req) {
  if (!py::isinstance<py::array>(obj))
    throw py::type_error(name + ": expected a numpy float32 array, got " +
                         std::string(py::str(py::type::of(obj).attr("__name__"))));
  const py::array a = py::reinterpret_borrow<py::array>(obj);
  if (!a.dtype().is(py::dtype::of<float>()))
    throw py::type_error(name + ": expected dtype float32, got " + std::string(py::str(a.dtype())) +
                         " (convert with a.astype(numpy.float32))");
  if (a.ndim() != 2 && a.ndim() != 3)
    throw py::value_error(name + ": expected shape (H, W) or (H, W, C), got " +
                          std::to_string(a.ndim()) + " dimensions");
  const int channels = a.ndim() == 2 ? 1 : int(a.shape(2));
  if (a.shape(0) < 1 || a.shape(1) < 1) throw py::value_error(name + ": the image is empty");
  if (channels < req.min_channels || channels > req.max_channels)
    throw py::value_error(
        name + ": expected " + std::to_string(req.min_channels) +
        (req.min_channels == req.max_channels ? "" : " to " + std::to_string(req.max_channels)) +
        " channels, got " + std::to_string(channels));
  if (!(a.flags() & py::array::c_style))
    throw py::value_error(name +
                          ": the array is not C-contiguous (pass numpy.ascontiguousarray(a))");
  if (a.shape(0) > 65536 || a.shape(1) > 65536)
    throw py::value_error(name + ": larger than 65536 pixels on a side");
  Image image(int(a.shape(1)), int(a.shape(0)), channels);
  std::memcpy(image.data.data(), a.data(), image.data.size() * sizeof(float));
  if (req.finite || req.non_negative) {
    for (std::size_t i = 0; i < image.data.size(); ++i) {
      const float v = image.data[i];
      const bool bad = (req.finite && !std::isfinite(v)) || (req.non_negative && v < 0.0f);
      if (!bad) continue;
      const std::size_t px = i / std::size_t(channels);
      throw py::value_error(
          name + ": pixel (row " + std::to_string(px / image.width) + ", column " +
          std::to_string(px % image.width) + ") holds " + std::to_string(v) +
          (req.non_negative ? "; values must be finite and >= 0" : "; values must be finite"));
    }
  }
  return image;
}

py::array_t<float> array_from_image(Image&& image) {
  auto* pixels = new std::vector<float>(std::move(image.data));
  py::capsule owner(pixels, [](void* p) { delete static_cast<std::vector<float>*>(p); });
  std::vector<py::ssize_t> shape{image.height, image.width};
  if (image.channels != 1) shape.push_back(image.channels);
  return py::array_t<float>(shape, pixels->data(), owner);
}

}  // namespace pbrkit::python
