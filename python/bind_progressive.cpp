// The accumulation behind pathlab.render_progressive: one render continued
// pass after pass (render/accumulation.h), so that the image after each pass
// is the render of its spp bit for bit while the whole costs about one render
// of the last spp — not the sum of renders from scratch.
#include <pybind11/stl.h>

#include <memory>
#include <string>

#include "core/error.h"
#include "render/accumulation.h"
#include "render_binding.h"

namespace pathlab::python {
namespace {

class Progressive {
  public:
    // `keywords.spp` is the last pass's count: the settings are checked once,
    // for it, as render() checks them.
    Progressive(Scene scene, const RenderKeywords& keywords)
        : scene_(std::move(scene)),
          settings_(settingsFor(scene_, keywords)),
          accumulation_(withControl(settings_, &control_)) {}

    // The image at `spp` samples per pixel, adding only what the last pass
    // lacked (everything, for a sampler that is not progressive).
    py::object advance(int64_t spp, const py::object& progress, double interval, bool withStats) {
        if (spp <= accumulation_.spp() || spp > settings_.samplesPerPixel)
            throw InputError("spp must be between " + std::to_string(accumulation_.spp() + 1) +
                             " and " + std::to_string(settings_.samplesPerPixel) + ", got " +
                             std::to_string(spp));
        // The GIL is released while rendering: refuse a second caller.
        if (busy_) throw InputError("this progressive render is already rendering");
        busy_ = true;
        control_.cancel = false, control_.tilesDone = 0;
        try {
            runReleased([&] { accumulation_.advance(*scene_.scene, int(spp)); }, control_, progress,
                        interval);
        } catch (...) {
            busy_ = false;
            throw;
        }
        busy_ = false;
        py::array_t<float> image = arrayFromImage(accumulation_.image());
        if (!withStats) return image;
        RenderSettings passSettings = settings_;
        passSettings.samplesPerPixel = int(spp);
        py::dict stats = statsDict(accumulation_.lastPass(), passSettings);
        stats["variance"] = arrayFromImage(accumulation_.varianceOfMean());
        stats["continued"] = accumulation_.progressive();
        return py::make_tuple(image, stats);
    }

    int spp() const { return accumulation_.spp(); }
    bool continues() const { return accumulation_.progressive(); }

  private:
    static RenderSettings withControl(RenderSettings s, RenderControl* control) {
        s.control = control;
        return s;
    }

    Scene scene_;  // held: the passes need it even if Python drops it
    RenderSettings settings_;
    RenderControl control_;
    Accumulation accumulation_;
    bool busy_ = false;  // read and written with the GIL held
};

}  // namespace

void bindProgressive(py::module_& m) {
    py::class_<Progressive>(m, "Progressive")
        .def(py::init([](Scene scene, std::optional<std::string> sampler, int64_t spp,
                         std::optional<std::string> seed, std::optional<std::string> size,
                         std::optional<int64_t> maxDepth, bool russianRoulette,
                         int64_t rouletteDepth, int64_t threads, bool spectral) {
                 const RenderKeywords k{sampler,  seed,          size,    spp,
                                        maxDepth, rouletteDepth, threads, russianRoulette,
                                        spectral};
                 return std::make_unique<Progressive>(std::move(scene), k);
             }),
             py::arg("scene"), py::arg("sampler"), py::arg("spp"), py::arg("seed"), py::arg("size"),
             py::arg("max_depth"), py::arg("russian_roulette"), py::arg("roulette_depth"),
             py::arg("threads"), py::arg("spectral"))
        .def("advance", &Progressive::advance, py::arg("spp"), py::arg("progress"),
             py::arg("interval"), py::arg("with_stats"))
        .def_property_readonly("spp", &Progressive::spp)
        .def_property_readonly("continues", &Progressive::continues);
}

}  // namespace pathlab::python
