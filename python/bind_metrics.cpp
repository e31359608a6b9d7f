// pathlab.mse / rmse / relmse / psnr / flip / flip_map / error_spectrum /
// low_frequency_fraction: the library calls
// `pathlab compare` makes, in its order, so each number equals its --json
// output to the last bit.
#include <pybind11/stl.h>

#include <cmath>
#include <optional>

#include "bindings.h"
#include "core/error.h"
#include "metrics/error_spectrum.h"
#include "metrics/flip.h"
#include "metrics/image_metrics.h"

namespace pathlab::python {
namespace {

struct ImagePair {
    Image reference, test;
};

// Both arrays as images, checked as `pathlab compare` checks its files.
ImagePair pairOf(const py::array& reference, const py::array& test) {
    ImagePair p{imageFromArray(reference, "reference"), imageFromArray(test, "test")};
    requireComparable(p.reference, p.test, "reference", "test");
    return p;
}

flip::Options flipOptions(const std::string& mode, std::optional<double> ppd) {
    flip::Options options;
    if (mode != "hdr" && mode != "ldr")
        throw InputError("mode must be 'hdr' or 'ldr', got '" + mode + "'");
    options.mode = mode == "ldr" ? flip::Mode::Ldr : flip::Mode::Hdr;
    if (ppd) {
        // compare's --ppd bounds (its filters grow with the pixels per degree).
        if (!(*ppd >= 1 && *ppd <= 1000))
            throw InputError("ppd must be a number of pixels per degree between 1 and 1000, got " +
                             std::to_string(*ppd));
        options.ppd = float(*ppd);
    }
    return options;
}

flip::Result flipOf(const py::array& reference, const py::array& test, const std::string& mode,
                    std::optional<double> ppd) {
    const ImagePair p = pairOf(reference, test);
    const flip::Options options = flipOptions(mode, ppd);
    py::gil_scoped_release release;
    return flip::evaluate(p.reference, p.test, options);
}

// The keys of `pathlab compare --json`'s "flip" object.
py::dict flipDict(const flip::Result& f) {
    py::dict d;
    d["mean"] = f.stats.mean;
    d["weighted_median"] = f.stats.weightedMedian;
    d["q1"] = f.stats.q1;
    d["q3"] = f.stats.q3;
    d["min"] = f.stats.min;
    d["max"] = f.stats.max;
    d["ppd"] = f.ppd;
    d["mode"] = f.mode == flip::Mode::Ldr ? "ldr" : "hdr";
    if (f.mode == flip::Mode::Hdr) {
        py::dict e;
        e["start"] = f.exposures.start;
        e["stop"] = f.exposures.stop;
        e["count"] = f.exposures.count;
        d["exposures"] = e;
    } else {
        d["exposures"] = py::none();
    }
    return d;
}

// The spectrum `pathlab compare --error-spectrum` writes, as two arrays.
py::tuple errorSpectrumArrays(const py::array& reference, const py::array& test) {
    const ImagePair p = pairOf(reference, test);
    RadialPowerSpectrum s;
    {
        py::gil_scoped_release release;
        s = errorSpectrum(p.reference, p.test);
    }
    py::array_t<double> frequency(py::ssize_t(s.frequency.size()));
    py::array_t<double> power(py::ssize_t(s.power.size()));
    std::copy(s.frequency.begin(), s.frequency.end(), frequency.mutable_data());
    std::copy(s.power.begin(), s.power.end(), power.mutable_data());
    return py::make_tuple(frequency, power);
}

}  // namespace

void bindMetrics(py::module_& m) {
    const auto ref = py::arg("reference"), test = py::arg("test");
    m.def(
        "mse",
        [](const py::array& r, const py::array& t) {
            const ImagePair p = pairOf(r, t);
            return meanSquaredError(p.reference, p.test);
        },
        ref, test);
    m.def(
        "rmse",
        [](const py::array& r, const py::array& t) {
            const ImagePair p = pairOf(r, t);
            return std::sqrt(meanSquaredError(p.reference, p.test));  // as compare
        },
        ref, test);
    m.def(
        "relmse",
        [](const py::array& r, const py::array& t, double epsilon) {
            if (!(epsilon > 0 && std::isfinite(epsilon)))
                throw InputError("epsilon must be a positive number, got " +
                                 std::to_string(epsilon));
            const ImagePair p = pairOf(r, t);
            return relativeMeanSquaredError(p.reference, p.test, epsilon);
        },
        ref, test, py::arg("epsilon") = kRelMseEpsilon);
    m.def(
        "psnr",
        [](const py::array& r, const py::array& t, double peak) {
            if (!(peak > 0 && std::isfinite(peak)))
                throw InputError("peak must be a positive number, got " + std::to_string(peak));
            const ImagePair p = pairOf(r, t);
            return psnrFromMse(meanSquaredError(p.reference, p.test), peak);
        },
        ref, test, py::arg("peak") = 1.0);
    m.def(
        "flip",
        [](const py::array& r, const py::array& t, const std::string& mode,
           std::optional<double> ppd) { return flipDict(flipOf(r, t, mode, ppd)); },
        ref, test, py::arg("mode"), py::arg("ppd"));
    m.def(
        "flip_map",
        [](const py::array& r, const py::array& t, const std::string& mode,
           std::optional<double> ppd) {
            const flip::Result f = flipOf(r, t, mode, ppd);
            py::array_t<float> map({size_t(f.height), size_t(f.width)});
            std::copy(f.errorMap.begin(), f.errorMap.end(), map.mutable_data());
            return map;
        },
        ref, test, py::arg("mode"), py::arg("ppd"));
    m.def("error_spectrum", errorSpectrumArrays, ref, test);
    m.def(
        "low_frequency_fraction",
        [](const py::array& r, const py::array& t) -> std::optional<double> {
            const ImagePair p = pairOf(r, t);
            const double f = lowFrequencyErrorFraction(p.reference, p.test);
            if (std::isnan(f)) return std::nullopt;  // compare --json's null
            return f;
        },
        ref, test);
    m.attr("LOW_FREQUENCY_LIMIT") = kLowFrequencyLimit;
    m.attr("RELMSE_EPSILON") = kRelMseEpsilon;
}

}  // namespace pathlab::python
