// `pathlab compare REFERENCE TEST`: image metrics between two images.
#include <cmath>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "core/error.h"
#include "core/image.h"
#include "core/json_null.h"
#include "metrics/bias.h"
#include "metrics/error_map.h"
#include "metrics/error_spectrum.h"
#include "metrics/flip.h"
#include "metrics/image_metrics.h"
#include "render/emitter_edges.h"
#include "scene/loader.h"

namespace pathlab::cli {
namespace {

struct CompareArgs {
    std::string reference, test;
    std::string metric = "all";
    bool json = false;
    std::string errorMap;
    std::string errorSpectrum;  // CSV or PNG of the error's radial power spectrum
    bool ldr = false, hdr = false;
    std::string ppd;      // "": the default viewing conditions; else parsePpd
    std::string regions;  // a scene: also split the MSE by its emitter edge
};

// FLIP's filters grow with the pixels per degree (and with them the memory
// and the time), so the value is bounded to what a display or print can be
// viewed at: from 1 (a coarse projector from close by) to 1000 (a fine print
// from afar). Read as text: CLI11 turns "nan" into a number.
constexpr double kMinPpd = 1, kMaxPpd = 1000;

float parsePpd(const std::string& text) {
    size_t used = 0;
    double v = 0;
    try {
        v = std::stod(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used == 0 || used != text.size() || !(v >= kMinPpd && v <= kMaxPpd))
        throw InputError("--ppd must be a number of pixels per degree between 1 and 1000, got '" +
                         text + "'");
    return float(v);
}

struct CompareResults {
    double mse = 0, rmse = 0, relmse = 0, psnr = 0;
    Bias bias;
    bool hasPixelMetrics = false;
    std::optional<RegionMse> regions;             // with --regions
    std::optional<RadialPowerSpectrum> spectrum;  // with --metric all or --error-spectrum
    std::unique_ptr<flip::Result> flip;
};

bool wants(const CompareArgs& a, const char* metric) {
    return a.metric == "all" || a.metric == metric;
}

CompareResults computeMetrics(const CompareArgs& args, const Image& ref, const Image& test,
                              float ppd, const std::vector<uint8_t>* edgeMask) {
    CompareResults out;
    if (args.metric != "flip") {
        out.hasPixelMetrics = true;
        out.mse = meanSquaredError(ref, test);
        out.rmse = std::sqrt(out.mse);
        out.relmse = relativeMeanSquaredError(ref, test);
        out.psnr = psnrFromMse(out.mse);
        out.bias = signedBias(ref, test);
        if (edgeMask) out.regions = meanSquaredErrorByRegion(ref, test, *edgeMask);
    }
    if (args.metric == "all" || !args.errorSpectrum.empty())
        out.spectrum = errorSpectrum(ref, test);
    if (wants(args, "flip") || !args.errorMap.empty()) {
        flip::Options options;
        options.mode = args.ldr   ? flip::Mode::Ldr
                       : args.hdr ? flip::Mode::Hdr
                                  : flipModeForFiles(args.reference, args.test);
        if (ppd > 0) options.ppd = ppd;
        out.flip = std::make_unique<flip::Result>(flip::evaluate(ref, test, options));
    }
    return out;
}

// JSON has no infinity: PSNR of identical images is written as null.
nlohmann::json finiteOrNull(double v) {
    return std::isfinite(v) ? nlohmann::json(v) : nullptr;
}

nlohmann::json flipJson(const flip::Result& f) {
    nlohmann::json j = {
        {"mean", f.stats.mean}, {"weighted_median", f.stats.weightedMedian},
        {"q1", f.stats.q1},     {"q3", f.stats.q3},
        {"min", f.stats.min},   {"max", f.stats.max},
        {"ppd", f.ppd},         {"mode", f.mode == flip::Mode::Ldr ? "ldr" : "hdr"}};
    if (f.mode == flip::Mode::Hdr)
        j["exposures"] = {
            {"start", f.exposures.start}, {"stop", f.exposures.stop}, {"count", f.exposures.count}};
    else
        j["exposures"] = nullptr;
    return j;
}

void printJson(const CompareArgs& args, const CompareResults& r) {
    nlohmann::json j = nlohmann::json::object();
    if (r.hasPixelMetrics) {
        if (wants(args, "mse")) j["mse"] = r.mse;
        if (wants(args, "rmse")) j["rmse"] = r.rmse;
        if (wants(args, "relmse")) {
            j["relmse"] = r.relmse;
            j["relmse_epsilon"] = kRelMseEpsilon;
        }
        if (wants(args, "psnr")) j["psnr"] = finiteOrNull(r.psnr);
        if (wants(args, "bias"))
            j["bias"] = {{"mean", r.bias.mean},
                         {"relative", orNull<nlohmann::json>(r.bias.relative)},
                         {"channels", r.bias.channels}};
    }
    if (r.spectrum)
        j["low_frequency_fraction"] = finiteOrNull(lowFrequencyErrorFraction(*r.spectrum));
    if (r.regions) {
        j["regions"] = {{"scene", args.regions},
                        {"edge_pixels", r.regions->insidePixels},
                        {"mse_edge", orNull<nlohmann::json>(r.regions->inside)},
                        {"mse_rest", orNull<nlohmann::json>(r.regions->outside)}};
    }
    if (r.flip) j["flip"] = flipJson(*r.flip);
    std::printf("%s\n", j.dump().c_str());
}

void printText(const CompareArgs& args, const CompareResults& r) {
    if (r.hasPixelMetrics) {
        if (wants(args, "mse")) std::printf("mse     %.6g\n", r.mse);
        if (wants(args, "rmse")) std::printf("rmse    %.6g\n", r.rmse);
        if (wants(args, "relmse"))
            std::printf("relmse  %.6g  (epsilon %g)\n", r.relmse, kRelMseEpsilon);
        if (wants(args, "psnr")) std::printf("psnr    %.4f dB\n", r.psnr);
        if (wants(args, "bias")) {
            const Bias& b = r.bias;
            std::printf("bias    %.6g  (r %.6g  g %.6g  b %.6g)", b.mean, b.channels[0],
                        b.channels[1], b.channels[2]);
            if (b.relative) std::printf("  relative %+.6g", *b.relative);
            std::printf("\n");
        }
    }
    if (r.spectrum)
        std::printf("lowfreq %.6g  (share of the error's power below %g cycles/pixel)\n",
                    lowFrequencyErrorFraction(*r.spectrum), kLowFrequencyLimit);
    if (r.regions) {
        const auto value = [](const std::optional<double>& v) {
            char text[32] = "-";
            if (v) std::snprintf(text, sizeof text, "%.6g", *v);
            return std::string(text);
        };
        std::printf("regions mse %s on the %zu emitter-edge pixels of %s, %s elsewhere\n",
                    value(r.regions->inside).c_str(), r.regions->insidePixels, args.regions.c_str(),
                    value(r.regions->outside).c_str());
    }
    if (r.flip) {
        const flip::Result& f = *r.flip;
        std::printf(
            "flip    mean %.6f  weighted median %.6f  q1 %.6f  q3 %.6f  min %.6f  max %.6f\n",
            f.stats.mean, f.stats.weightedMedian, f.stats.q1, f.stats.q3, f.stats.min, f.stats.max);
        if (f.mode == flip::Mode::Ldr)
            std::printf("        LDR-FLIP at %.2f pixels per degree\n", f.ppd);
        else
            std::printf(
                "        HDR-FLIP at %.2f pixels per degree, %d exposures from %.4f to %.4f\n",
                f.ppd, f.exposures.count, f.exposures.start, f.exposures.stop);
    }
}

void runCompare(const CompareArgs& args) {
    // Refused before the images are read; 0 keeps FLIP's default.
    const float ppd = args.ppd.empty() ? 0.0f : parsePpd(args.ppd);
    // Fail before the work if the error map cannot be written.
    if (!args.errorMap.empty()) checkWritable(args.errorMap);
    if (!args.errorSpectrum.empty()) checkErrorSpectrumPath(args.errorSpectrum);
    const Image ref = readImage(args.reference);
    const Image test = readImage(args.test);
    requireComparable(ref, test, args.reference, args.test);
    // The scene's emitter edge as its camera frames an image of this size.
    std::vector<uint8_t> edgeMask;
    if (!args.regions.empty())
        edgeMask = emitterEdgePixels(RenderScene(loadScene(args.regions)), {ref.width, ref.height});
    const CompareResults results =
        computeMetrics(args, ref, test, ppd, args.regions.empty() ? nullptr : &edgeMask);
    if (!args.errorMap.empty())
        writeErrorMap(args.errorMap, results.flip->errorMap, results.flip->width,
                      results.flip->height);
    if (!args.errorSpectrum.empty()) writeErrorSpectrum(args.errorSpectrum, *results.spectrum);
    if (args.json)
        printJson(args, results);
    else
        printText(args, results);
}

}  // namespace

void addCompareCommand(CLI::App& app) {
    auto args = std::make_shared<CompareArgs>();
    CLI::App* cmd = app.add_subcommand(
        "compare",
        "Image metrics (MSE, RMSE, relMSE, PSNR, bias, FLIP, low-frequency error fraction) "
        "of TEST against REFERENCE");
    cmd->add_option("reference", args->reference, "Reference image (.exr, .png or .pfm)")
        ->required();
    cmd->add_option("test", args->test, "Test image, same size as the reference")->required();
    cmd->add_option("--metric", args->metric, "Metric to compute (default: all)")
        ->check(CLI::IsMember({"mse", "rmse", "relmse", "psnr", "bias", "flip", "all"}));
    cmd->add_flag("--json", args->json, "Print one JSON object on stdout");
    cmd->add_option("--error-map", args->errorMap,
                    "Write the FLIP error map: .png in the magma colour map, .exr/.pfm raw values");
    cmd->add_option("--error-spectrum", args->errorSpectrum,
                    "Write the radially averaged power spectrum of the signed error: .csv "
                    "(frequency,power) or .png (a log-scale plot)");
    auto* ldr = cmd->add_flag("--ldr", args->ldr, "Force LDR-FLIP (inputs clamped to [0,1])");
    auto* hdr =
        cmd->add_flag("--hdr", args->hdr, "Force HDR-FLIP (exposure range from the reference)");
    ldr->excludes(hdr);
    cmd->add_option(
        "--ppd", args->ppd,
        "FLIP pixels per degree, 1 to 1000 (default 67.02: 0.7 m from a 0.7 m wide 3840 px "
        "display)");
    cmd->add_option("--regions", args->regions,
                    "Also the MSE over the pixels where SCENE's visible emitters have their "
                    "outline (as its camera frames an image of this size) and over the rest");
    cmd->callback([args] { runCompare(*args); });
}

}  // namespace pathlab::cli
