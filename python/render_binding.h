// What pathlab.render and pathlab.render_progressive share: a loaded scene,
// the keywords read as `pathlab render` reads its flags, and running a render
// on a worker thread while the caller's thread watches for Ctrl-C.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "bindings.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace pathlab::python {

// A scene loaded once and rendered any number of times, from any thread.
struct Scene {
    std::string source;
    std::shared_ptr<const RenderScene> scene;
    RenderDefaults defaults;
    // How it was loaded, so that render(light_sampler=…) can load it again.
    bool lenient = false, solidAngleLights = false;
    std::string lightSampler;  // as asked; "": the file's own choice
};

// The Python keywords as `pathlab render` reads its flags; None is "not given".
struct RenderKeywords {
    std::optional<std::string> sampler, seed, size;
    std::optional<int64_t> spp, maxDepth;
    int64_t rouletteDepth = kDefaultRouletteDepth, threads = 0;
    bool russianRoulette = true;
    bool spectral = false;
};

// The checked settings (InputError naming the keyword otherwise).
RenderSettings settingsFor(const Scene& scene, const RenderKeywords& keywords);

// Runs `job` (a render watched by `control`) on a worker thread without the
// GIL while the calling thread, every `interval` seconds, checks for Ctrl-C
// (PyErr_CheckSignals: only the main thread sees signals) and calls
// progress(done_tiles, total_tiles). Either raising stops the render at the
// next tile and re-raises here; so does an exception from `job`.
void runReleased(const std::function<void()>& job, RenderControl& control,
                 const py::object& progress, double interval);

// The stats dict of return_stats=True, without "variance".
py::dict statsDict(const RenderStats& stats, const RenderSettings& settings);

}  // namespace pathlab::python
