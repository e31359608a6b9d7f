// The compiled core of the `pathlab` Python package (python/pathlab/ wraps it
// with keyword arguments and docstrings; docs/python.md).
#include <pybind11/pybind11.h>

#include <algorithm>
#include <cstring>

#include "bindings.h"
#include "core/error.h"

namespace pathlab::python {

Image imageFromArray(const py::array& array, const std::string& argument) {
    const auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(array);
    if (!a || a.ndim() != 3 || a.shape(2) != 3 || a.shape(0) < 1 || a.shape(1) < 1)
        throw InputError(argument + " must be an H×W×3 array of linear RGB");
    if (a.shape(0) > kMaxImageSide || a.shape(1) > kMaxImageSide)
        throw InputError(argument + " must be at most " + std::to_string(kMaxImageSide) +
                         " pixels wide and tall");
    Image image(int(a.shape(1)), int(a.shape(0)));
    std::memcpy(image.rgb.data(), a.data(), image.rgb.size() * sizeof(float));
    return image;
}

py::array_t<float> arrayFromImage(const Image& image) {
    py::array_t<float> a({size_t(image.height), size_t(image.width), size_t(3)});
    std::copy(image.rgb.begin(), image.rgb.end(), a.mutable_data());
    return a;
}

}  // namespace pathlab::python

PYBIND11_MODULE(_pathlab, m) {
    using namespace pathlab::python;
    m.doc() = "pathlab's engine; use the `pathlab` package, which documents each function.";
    // The user's mistakes (the CLI's exit code 2) are ValueErrors with the
    // CLI's one-line message.
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const pathlab::InputError& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        }
    });
    bindRender(m);
    bindProgressive(m);
    bindMetrics(m);
    bindSampling(m);
    bindStudy(m);
    m.def(
        "read_image",
        [](const std::string& path) { return arrayFromImage(pathlab::readImage(path)); },
        py::arg("path"));
    m.def(
        "write_image",
        [](const std::string& path, const py::array& image, float exposure) {
            pathlab::writeImage(path, imageFromArray(image, "image"), exposure);
        },
        py::arg("path"), py::arg("image"), py::arg("exposure"));
}
