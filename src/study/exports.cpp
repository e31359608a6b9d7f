#include "study/exports.h"

#include <cstdio>

#include "core/json_null.h"
#include "study/bias_analysis.h"
#include "study/files.h"

namespace pathlab {
namespace {

using Json = nlohmann::ordered_json;

Json cellJson(const CellRow& c) {
    return {{"scene", c.key.scene},
            {"sampler", c.key.sampler},
            {"spp", c.key.spp},
            {"seed", c.key.seed},
            {"seconds", c.seconds},
            {"mse", c.mse},
            {"rmse", c.rmse},
            {"relmse", orNull(c.relmse)},
            {"flip", orNull(c.flip)},
            {"flip_median", orNull(c.flipMedian)},
            {"psnr", orNull(c.psnr)},
            {"bias", orNull(c.bias)},
            {"low_frequency_fraction", orNull(c.lowFrequencyFraction)},
            {"mse_edge", orNull(c.mseEdge)},
            {"mse_rest", orNull(c.mseRest)},
            {"nonfinite", c.nonFinite},
            {"image", c.image},
            {"width", c.width},
            {"height", c.height},
            {"max_depth", c.maxDepth},
            {"threads", c.threads},
            // An external cell's file hash; finished_at stays the last column.
            {"source_hash", c.sourceHash.empty() ? Json(nullptr) : Json(c.sourceHash)},
            {"git_commit", c.gitCommit},
            {"finished_at", c.finishedAt}};
}

Json referenceJson(const ReferenceRow& r) {
    return {{"scene", r.scene},
            {"sampler", r.sampler},
            {"spp", r.spp},
            {"seconds", r.seconds},
            {"cache_key", r.cacheKey},
            {"noise_mse", r.noiseMse},
            {"noise_relmse", r.noiseRelmse},
            {"noise_mse_edge", orNull(r.noiseMseEdge)},
            {"noise_mse_rest", orNull(r.noiseMseRest)},
            {"edge_pixels", r.edgePixels ? Json(*r.edgePixels) : Json(nullptr)},
            {"exposure", r.exposure},
            {"image", r.image}};
}

// Round-trip precision, so the CSV holds exactly what the database holds.
std::string number(double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.17g", v);
    return buffer;
}

std::string csvField(const Json& v) {
    if (v.is_null()) return "";
    if (v.is_number_float()) return number(v.get<double>());
    if (!v.is_string()) return v.dump();
    const std::string s = v.get<std::string>();
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string quoted = "\"";
    for (char ch : s) quoted += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    return quoted + "\"";
}

}  // namespace

const std::vector<std::string>& cellColumns() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> out;
        const Json empty = cellJson(CellRow{});  // kept alive: items() refers to it
        for (const auto& item : empty.items()) out.push_back(item.key());
        return out;
    }();
    return names;
}

std::string cellsCsv(const std::vector<CellRow>& cells) {
    std::string out;
    for (const std::string& name : cellColumns()) {
        if (!out.empty()) out += ',';
        out += name;
    }
    out += "\n";
    for (const CellRow& c : cells) {
        std::string line;
        const Json row = cellJson(c);
        for (const auto& item : row.items()) {
            if (!line.empty()) line += ',';
            line += csvField(item.value());
        }
        out += line + "\n";
    }
    return out;
}

void writeExports(const std::filesystem::path& dir, const ResultsStore& store,
                  const nlohmann::ordered_json& analysis) {
    const std::vector<CellRow> cells = store.cells();
    Json study = Json::object();
    for (const auto& [key, value] : store.studyValues()) study[key] = value;
    Json cellList = Json::array(), referenceList = Json::array();
    for (const CellRow& c : cells) cellList.push_back(cellJson(c));
    for (const ReferenceRow& r : store.references()) referenceList.push_back(referenceJson(r));
    const Json results = {{"study", study},
                          {"cells", cellList},
                          {"references", referenceList},
                          {"analysis", analysis}};
    writeTextFileAtomic(dir / "results.csv", cellsCsv(cells));
    writeTextFileAtomic(dir / "bias.csv", biasCsv(analyzeBias(cells)));
    writeTextFileAtomic(dir / "results.json", results.dump(1) + "\n");
    writeTextFileAtomic(dir / "analysis.json", analysis.dump(1) + "\n");
}

}  // namespace pathlab
