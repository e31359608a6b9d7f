#include "study/summary.h"

#include <algorithm>
#include <cstdio>
#include <string>

namespace pathlab {
namespace {

using Json = nlohmann::ordered_json;

std::string format(const char* pattern, double v) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, pattern, v);
    return buffer;
}

// The spp columns: 1, 8 and 64 when the study has them (else its smallest),
// and always its largest, where samplers differ the most.
std::vector<std::string> ratioColumns(const Json& scene) {
    std::vector<std::string> spps;
    for (const auto& [name, sampler] : scene.at("samplers").items())
        for (const auto& item : sampler.at("by_spp").items())
            if (std::find(spps.begin(), spps.end(), item.key()) == spps.end())
                spps.push_back(item.key());
    if (spps.empty()) return {};
    const auto byValue = [](const std::string& a, const std::string& b) {
        return std::stol(a) < std::stol(b);
    };
    std::sort(spps.begin(), spps.end(), byValue);
    std::vector<std::string> out;
    for (const char* wanted : {"1", "8", "64"})
        if (std::find(spps.begin(), spps.end(), wanted) != spps.end()) out.push_back(wanted);
    if (out.empty()) out.push_back(spps.front());
    if (out.back() != spps.back()) out.push_back(spps.back());
    return out;
}

// A ratio table's entry at `spp` to three decimals, or "-" where it has none.
std::string ratioText(const Json& ratios, const std::string& spp) {
    if (ratios.is_null() || !ratios.contains(spp) || ratios.at(spp).is_null()) return "-";
    return format("%.3f", ratios.at(spp).get<double>());
}

std::string ratioCell(const Json& sampler, const std::string& spp) {
    const std::string text = ratioText(sampler.at("mse_ratio_to_independent"), spp);
    if (text == "-") return text;
    const bool floor = sampler.at("by_spp").at(spp).value("below_noise_floor", false);
    return text + (floor ? "*" : " ");
}

// A sampler's ratio over one region ("edge" or "rest") at `spp`, or "-".
std::string regionCell(const Json& sampler, const char* region, const std::string& spp) {
    return ratioText(sampler.at("mse_ratio_by_region").at(region), spp);
}

// "emitter edge: 112 of 65536 pixels, 86% of independent's error at 16 spp".
std::string regionLine(const Json& scene, const std::string& spp) {
    const Json& regions = scene.at("regions");
    if (regions.is_null()) return "";
    std::string out = "  emitter edge: " + regions.at("edge_pixels").dump() + " of " +
                      regions.at("pixels").dump() + " pixels";
    const Json& share = regions.at("independent_edge_share");
    if (!share.is_null() && share.contains(spp) && !share.at(spp).is_null())
        out += format(", %.0f%%", 100 * share.at(spp).get<double>()) +
               " of independent's error at " + spp + " spp";
    return out + "\n";
}

std::string sceneHeader(const std::string& name, const Json& scene,
                        const std::vector<ReferenceRow>& references) {
    std::string out = name;
    for (const ReferenceRow& r : references)
        if (r.scene == name) out += ": reference " + std::to_string(r.spp) + " spp " + r.sampler;
    out += format(", noise floor MSE %.3g", scene.at("noise_floor_mse").get<double>());
    if (!scene.at("target_mse").is_null())
        out += format("; target MSE %.3g", scene.at("target_mse").get<double>()) + " (" +
               Json(scene.at("target_spp")).dump() + " spp standard)";
    return out + "\n";
}

std::string sceneTable(const std::string& name, const Json& scene,
                       const std::vector<ReferenceRow>& references) {
    const std::vector<std::string> columns = ratioColumns(scene);
    const std::string last = columns.empty() ? "" : columns.back();
    const bool regions = !scene.at("regions").is_null() && !last.empty();
    std::string out =
        sceneHeader(name, scene, references) + (regions ? regionLine(scene, last) : "");
    char line[256];
    std::snprintf(line, sizeof line, "  %-12s %7s", "sampler", "slope");
    out += line;
    for (const std::string& spp : columns) {
        std::snprintf(line, sizeof line, "  %9s", ("ind@" + spp).c_str());
        out += line;
    }
    if (regions) {
        std::snprintf(line, sizeof line, "  %9s  %9s", ("edge@" + last).c_str(),
                      ("rest@" + last).c_str());
        out += line;
    }
    out += "  time to target\n";
    for (const auto& [sampler, s] : scene.at("samplers").items()) {
        const Json& slope = s.at("slope_mse");
        std::snprintf(line, sizeof line, "  %-12s %7s", sampler.c_str(),
                      slope.is_null() ? "-" : format("%.2f", slope.get<double>()).c_str());
        out += line;
        for (const std::string& spp : columns) {
            std::snprintf(line, sizeof line, "  %9s", ratioCell(s, spp).c_str());
            out += line;
        }
        if (regions) {
            std::snprintf(line, sizeof line, "  %9s  %9s", regionCell(s, "edge", last).c_str(),
                          regionCell(s, "rest", last).c_str());
            out += line;
        }
        const Json& t = s.at("time_to_target_seconds");
        out += t.is_null() ? "  never" : "  " + format("%.3g s", t.get<double>());
        out += "\n";
    }
    return out;
}

}  // namespace

std::string summaryTable(const Json& analysis, const std::vector<ReferenceRow>& references) {
    std::string out;
    for (const auto& [name, scene] : analysis.at("scenes").items())
        out += sceneTable(name, scene, references) + "\n";
    out +=
        "slope: of log(MSE - noise floor) against log spp; ind@N: MSE ratio to independent\n"
        "at N spp (below 1 is better); * within 2× the reference's noise floor, not\n"
        "meaningful; edge@N, rest@N: the same ratio over the pixels a visible emitter's\n"
        "outline crosses and over all others; time to target: render time to reach\n"
        "standard's MSE at its largest spp.\n";
    return out;
}

}  // namespace pathlab
