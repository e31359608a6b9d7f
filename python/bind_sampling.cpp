// pathlab.samplers and pathlab.points: the registry `pathlab samplers` lists
// and the draws `pathlab points` writes (sampleDimensions, the renderer's
// own draw order).
#include <pybind11/stl.h>

#include <variant>
#include <vector>

#include "bindings.h"
#include "core/error.h"
#include "core/seed.h"
#include "sampling/registry.h"

namespace pathlab::python {
namespace {

// `pathlab points`' limits.
constexpr int kMaxPoints = 1 << 22;
constexpr int kMaxSpp = 1 << 24;

py::list samplerList() {
    py::list list;
    for (const SamplerInfo& s : samplerInfos()) {
        py::dict d;
        d["name"] = s.name;
        d["description"] = s.description;
        d["dimensions"] = s.nativeDimensions == 0 ? py::object(py::none())
                                                  : py::object(py::int_(s.nativeDimensions));
        d["randomized"] = s.randomized;
        d["progressive"] = s.progressive;
        list.append(d);
    }
    return list;
}

// Dimension d of sample `index` as the renderer draws it: the x or y of the
// 2D draw that holds it, else a 1D draw.
template <typename S>
float oneDimension(S& sampler, Vec2i pixel, int index, int d) {
    if (d == dims::kPixel + 1 || (d > 0 && startsLayoutPair(d - 1)))
        return sampleDimensions(sampler, pixel, index, d - 1, d).y;
    return sampleDimensions(sampler, pixel, index, d, d + 1).x;
}

struct PointsRequest {
    std::string sampler;
    int count = 0;
    std::vector<int> dims;
    Vec2i pixel;
    std::optional<Vec2i> resolution;
    std::optional<int64_t> spp;
    std::string seed;
};

void checkPointsRequest(const PointsRequest& r) {
    if (r.count < 1 || r.count > kMaxPoints)
        throw InputError("count must be between 1 and " + std::to_string(kMaxPoints) + ", got " +
                         std::to_string(r.count));
    if (r.spp && (*r.spp < 1 || *r.spp > kMaxSpp))
        throw InputError("spp must be between 1 and " + std::to_string(kMaxSpp) + ", got " +
                         std::to_string(*r.spp));
    if (r.dims.empty()) throw InputError("dims must name at least one dimension");
    for (int d : r.dims)
        if (d < 0 || d > (1 << 20))
            throw InputError("dims must be between 0 and 1048576, got " + std::to_string(d));
    if (r.dims.size() == 2 && r.dims[0] == r.dims[1])
        throw InputError("dims must name two different dimensions, got (" +
                         std::to_string(r.dims[0]) + ", " + std::to_string(r.dims[1]) + ")");
    const Vec2i res = r.resolution.value_or(Vec2i{r.pixel.x + 1, r.pixel.y + 1});
    if (res.x < 1 || res.y < 1 || res.x > kMaxImageSide || res.y > kMaxImageSide)
        throw InputError("resolution must be between 1x1 and " + std::to_string(kMaxImageSide) +
                         "x" + std::to_string(kMaxImageSide));
    if (r.pixel.x < 0 || r.pixel.y < 0 || r.pixel.x >= res.x || r.pixel.y >= res.y)
        throw InputError("pixel (" + std::to_string(r.pixel.x) + ", " + std::to_string(r.pixel.y) +
                         ") is not inside the image");
}

py::array_t<float> points(const PointsRequest& r) {
    checkPointsRequest(r);
    const Vec2i res = r.resolution.value_or(Vec2i{r.pixel.x + 1, r.pixel.y + 1});
    const int spp = r.spp ? int(*r.spp) : r.count;
    AnySampler sampler = makeSampler(r.sampler, SamplerConfig{spp, parseSeed(r.seed, "seed"), res});
    const size_t width = r.dims.size();
    py::array_t<float> out({size_t(r.count), width});
    float* p = out.mutable_data();
    py::gil_scoped_release release;
    std::visit(
        [&](auto& s) {
            for (int k = 0; k < r.count; ++k, p += width) {
                if (width == 2) {  // exactly `pathlab points --dims I,J`
                    const Vec2f v = sampleDimensions(s, r.pixel, k, r.dims[0], r.dims[1]);
                    p[0] = v.x, p[1] = v.y;
                } else {
                    for (size_t j = 0; j < width; ++j)
                        p[j] = oneDimension(s, r.pixel, k, r.dims[j]);
                }
            }
        },
        sampler);
    return out;
}

}  // namespace

void bindSampling(py::module_& m) {
    m.def("samplers", &samplerList);
    m.def(
        "points",
        [](const std::string& sampler, int count, std::vector<int> dims, std::pair<int, int> pixel,
           std::string seed, std::optional<int64_t> spp,
           std::optional<std::pair<int, int>> resolution) {
            PointsRequest r{sampler, count, std::move(dims), {pixel.first, pixel.second},
                            {},      spp,   std::move(seed)};
            if (resolution) r.resolution = Vec2i{resolution->first, resolution->second};
            return points(r);
        },
        py::arg("sampler"), py::arg("count"), py::arg("dims"), py::arg("pixel"), py::arg("seed"),
        py::arg("spp"), py::arg("resolution"));
}

}  // namespace pathlab::python
