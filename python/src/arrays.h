#pragma once
// numpy arrays <-> pbrkit::Image. Images cross as float32 arrays of shape (H, W) for one
// channel or (H, W, C) for C in 2..4, row 0 at the top, as Image stores them. An array
// handed in must already be float32 and C-contiguous: a silent conversion would hide a
// copy of a large image (and a float64 array's precision loss) from the caller, so the
// checks raise TypeError / ValueError naming the argument and the fix instead.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>

#include "pbrkit/image/image.h"

namespace pbrkit::python {

struct ArrayRequirements {
  int min_channels = 1;
  int max_channels = 4;
  bool finite = true;         ///< refuse NaN and infinity (ValueError naming the pixel)
  bool non_negative = false;  ///< refuse negative values
};

/// A copy of `array` as an Image; `name` is the argument's name in error messages.
Image image_from_array(const pybind11::handle& array, const std::string& name,
                       const ArrayRequirements& req = {});

/// A float32 array that takes over `image`'s pixels (no copy): (H, W) for one channel,
/// (H, W, C) otherwise.
pybind11::array_t<float> array_from_image(Image&& image);

}  // namespace pbrkit::python
