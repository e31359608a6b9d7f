// The pieces of the _pathlab extension (docs/python.md): each bind_*.cpp adds
// one area of the API to the module; the arrays helpers convert images.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>

#include "core/image.h"

namespace pathlab::python {

namespace py = pybind11;

void bindRender(py::module_& m);
void bindProgressive(py::module_& m);
void bindMetrics(py::module_& m);
void bindSampling(py::module_& m);
void bindStudy(py::module_& m);

// An H×W×3 array (any real dtype, converted to float32) as an Image; throws
// InputError naming `argument` for any other shape.
Image imageFromArray(const py::array& array, const std::string& argument);

// The image as a new float32 H×W×3 array.
py::array_t<float> arrayFromImage(const Image& image);

}  // namespace pathlab::python
