// pathlab.load_scene / Scene and the render call behind pathlab.render: the
// same loader, option checks (render/render_options.h) and renderer as
// `pathlab render`, so an image equals the CLI's EXR bit for bit.
#include <pybind11/stl.h>

#include <chrono>
#include <climits>
#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "render/render_options.h"
#include "render/renderer.h"
#include "render_binding.h"
#include "scene/light_selection.h"
#include "scene/loader.h"

namespace pathlab::python {

RenderSettings settingsFor(const Scene& scene, const RenderKeywords& k) {
    static const RenderOptionNames names{"spp", "max_depth", "roulette_depth", "seed", "size"};
    RenderSettings s;
    RenderOptionValues v;
    v.samplerGiven = bool(k.sampler), v.sppGiven = bool(k.spp);
    v.seedGiven = bool(k.seed), v.depthGiven = bool(k.maxDepth);
    if (k.sampler) s.sampler = *k.sampler;
    if (k.spp) v.spp = *k.spp;
    if (k.seed) v.seed = *k.seed;
    if (k.maxDepth) v.maxDepth = *k.maxDepth;
    if (k.size) v.size = *k.size;
    v.rouletteDepth = k.rouletteDepth;
    v.russianRoulette = k.russianRoulette;
    // Narrowed so that validateRenderSettings names the value given.
    s.threads = int(std::clamp<int64_t>(k.threads, INT_MIN, INT_MAX));
    s.spectral = k.spectral;
    applySceneDefaults(scene.defaults, v, s);
    settleRenderSettings(v, names, s);
    return s;
}

void runReleased(const std::function<void()>& job, RenderControl& control,
                 const py::object& progress, double interval) {
    std::mutex mutex;
    std::condition_variable finished;
    bool done = false, raised = false;
    std::exception_ptr error;
    {
        py::gil_scoped_release release;
        std::thread worker([&] {
            try {
                job();
            } catch (...) {
                error = std::current_exception();
            }
            std::lock_guard<std::mutex> lock(mutex);
            done = true;
            finished.notify_one();
        });
        const auto step = std::chrono::duration<double>(interval);
        std::unique_lock<std::mutex> lock(mutex);
        while (!finished.wait_for(lock, step, [&] { return done; })) {
            if (raised) continue;
            lock.unlock();
            py::gil_scoped_acquire acquire;
            try {
                if (PyErr_CheckSignals() != 0) throw py::error_already_set();
                if (!progress.is_none())
                    progress(control.tilesDone.load(), control.tilesTotal.load());
            } catch (py::error_already_set& e) {
                e.restore();  // kept in the thread's error indicator until the join
                raised = true;
                control.cancel = true;
            }
            lock.lock();
        }
        lock.unlock();
        worker.join();
    }
    if (raised) throw py::error_already_set();
    if (error) std::rethrow_exception(error);
    if (!progress.is_none()) progress(control.tilesTotal.load(), control.tilesTotal.load());
}

py::dict statsDict(const RenderStats& stats, const RenderSettings& s) {
    py::dict d;
    d["seconds"] = stats.seconds;
    d["paths"] = stats.paths;
    d["rays"] = stats.rays;
    d["shadow_rays"] = stats.shadowRays;
    d["non_finite"] = stats.nonFinite;
    d["sampler"] = s.sampler;
    d["spp"] = s.samplesPerPixel;
    d["seed"] = s.seed;
    d["max_depth"] = s.maxDepth;
    d["spectral"] = s.spectral;
    return d;
}

namespace {

Scene loadPythonScene(const std::string& source, bool lenient, bool solidAngleLights,
                      const std::string& lightSampler) {
    if (!lightSampler.empty()) parseLightSelection(lightSampler, "light_sampler");
    py::gil_scoped_release release;
    SceneDescription desc = loadScene(source, {lenient});
    const RenderDefaults defaults = desc.defaults;
    // As `pathlab render --light-sampler`: chosen when the render scene is built.
    if (!lightSampler.empty()) desc.defaults.lightSampler = lightSampler;
    auto scene = std::make_shared<const RenderScene>(
        std::move(desc), solidAngleLights ? LightSampling::SolidAngle : LightSampling::Area);
    return {source, std::move(scene), defaults, lenient, solidAngleLights, lightSampler};
}

py::object renderScene(const Scene& scene, const RenderKeywords& keywords,
                       const py::object& progress, double interval, bool withStats) {
    RenderSettings settings = settingsFor(scene, keywords);
    RenderControl control;
    settings.control = &control;
    std::optional<RenderOutput> rendered;
    runReleased([&] { rendered.emplace(render(*scene.scene, settings)); }, control, progress,
                interval);
    const RenderOutput& out = *rendered;
    py::array_t<float> image = arrayFromImage(out.image);
    if (!withStats) return image;
    py::dict stats = statsDict(out.stats, settings);
    stats["variance"] = arrayFromImage(out.varianceOfMean);
    return py::make_tuple(image, stats);
}

}  // namespace

void bindRender(py::module_& m) {
    py::class_<Scene>(m, "Scene")
        .def_property_readonly("source", [](const Scene& s) { return s.source; })
        .def_property_readonly("lenient", [](const Scene& s) { return s.lenient; })
        .def_property_readonly("solid_angle_lights",
                               [](const Scene& s) { return s.solidAngleLights; })
        .def_property_readonly("light_sampler",
                               [](const Scene& s) {
                                   return s.lightSampler.empty() ? py::object(py::none())
                                                                 : py::str(s.lightSampler);
                               })
        .def_property_readonly("width",
                               [](const Scene& s) { return s.scene->description().resolution.x; })
        .def_property_readonly("height",
                               [](const Scene& s) { return s.scene->description().resolution.y; })
        .def_property_readonly(
            "defaults",
            [](const Scene& s) {
                py::dict d;
                const RenderDefaults& r = s.defaults;
                d["sampler"] = r.sampler.empty() ? py::object(py::none()) : py::str(r.sampler);
                d["spp"] =
                    r.samplesPerPixel > 0 ? py::object(py::int_(r.samplesPerPixel)) : py::none();
                d["seed"] = r.hasSeed ? py::object(py::int_(r.seed)) : py::none();
                d["max_depth"] = r.maxDepth >= 0 ? py::object(py::int_(r.maxDepth)) : py::none();
                return d;
            })
        .def("__repr__", [](const Scene& s) {
            const Vec2i r = s.scene->description().resolution;
            return "pathlab.Scene('" + s.source + "', " + std::to_string(r.x) + "x" +
                   std::to_string(r.y) + ")";
        });
    m.def("load_scene", &loadPythonScene, py::arg("source"), py::arg("lenient") = false,
          py::arg("solid_angle_lights") = false, py::arg("light_sampler") = "");
    m.def("builtin_scenes", &builtinSceneNames);
    m.def(
        "render",
        // By value: the render holds the scene even if Python drops it meanwhile.
        [](Scene scene, std::optional<std::string> sampler, std::optional<int64_t> spp,
           std::optional<std::string> seed, std::optional<std::string> size,
           std::optional<int64_t> maxDepth, bool russianRoulette, int64_t rouletteDepth,
           int64_t threads, bool spectral, const py::object& progress, double interval,
           bool withStats) {
            const RenderKeywords k{sampler,  seed,          size,    spp,
                                   maxDepth, rouletteDepth, threads, russianRoulette,
                                   spectral};
            return renderScene(scene, k, progress, interval, withStats);
        },
        py::arg("scene"), py::arg("sampler"), py::arg("spp"), py::arg("seed"), py::arg("size"),
        py::arg("max_depth"), py::arg("russian_roulette"), py::arg("roulette_depth"),
        py::arg("threads"), py::arg("spectral"), py::arg("progress"), py::arg("interval"),
        py::arg("with_stats"));
}

}  // namespace pathlab::python
