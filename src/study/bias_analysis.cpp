#include "study/bias_analysis.h"

#include <algorithm>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <cstdio>
#include <map>
#include <tuple>

#include "sampling/registry.h"

namespace pathlab {
namespace {

// Does the seed change the sampler's image? A pathlab sampler says so in the
// registry; an external renderer's ("name:sampler") is taken at its word, and
// is deterministic only when its seeds' images measure the same.
bool seedRandomizes(const std::string& sampler) {
    if (sampler.find(':') != std::string::npos) return true;
    const auto& infos = samplerInfos();
    const auto it = std::find_if(infos.begin(), infos.end(),
                                 [&](const SamplerInfo& i) { return i.name == sampler; });
    return it == infos.end() || it->randomized;
}

BiasRow summarize(const std::string& scene, const std::string& sampler, int spp,
                  const std::vector<double>& values, int seeds) {
    BiasRow row{scene, sampler, spp, seeds, std::nullopt, std::nullopt, kBiasTooFewSeeds};
    if (values.empty()) return row;
    const double n = double(values.size());
    double mean = 0;
    for (double v : values) mean += v;
    mean /= n;
    row.bias = mean;
    const bool allEqual =
        std::all_of(values.begin(), values.end(), [&](double v) { return v == values.front(); });
    if (!seedRandomizes(sampler) || (values.size() > 1 && allEqual)) {
        row.biased = kBiasDeterministic;
        return row;
    }
    if (values.size() < 2) return row;
    double sumSquares = 0;
    for (double v : values) sumSquares += (v - mean) * (v - mean);
    const double standardError = std::sqrt(sumSquares / (n - 1) / n);
    row.ci95 = studentT975(int(values.size()) - 1) * standardError;
    row.biased = std::abs(mean) - *row.ci95 > kBiasTolerance ? "1" : "0";
    return row;
}

std::string number(double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.17g", v);
    return buffer;
}

std::string optionalNumber(const std::optional<double>& v) {
    return v ? number(*v) : "";
}

// A field as CSV writes it: quoted when it holds a comma, quote or newline.
std::string csvText(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string quoted = "\"";
    for (char ch : s) quoted += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    return quoted + "\"";
}

}  // namespace

double studentT975(int dof) {
    return boost::math::quantile(boost::math::students_t(double(dof)), 0.975);
}

std::vector<BiasRow> analyzeBias(const std::vector<CellRow>& cells) {
    struct Group {
        std::vector<double> values;
        int seeds = 0;
    };
    std::vector<std::tuple<std::string, std::string, int>> order;
    std::map<std::tuple<std::string, std::string, int>, Group> groups;
    for (const CellRow& c : cells) {
        const auto key = std::make_tuple(c.key.scene, c.key.sampler, c.key.spp);
        const auto [it, added] = groups.try_emplace(key);
        if (added) order.push_back(key);
        ++it->second.seeds;
        if (c.bias) it->second.values.push_back(*c.bias);
    }
    std::vector<BiasRow> rows;
    for (const auto& key : order) {
        const Group& g = groups.at(key);
        rows.push_back(
            summarize(std::get<0>(key), std::get<1>(key), std::get<2>(key), g.values, g.seeds));
    }
    return rows;
}

std::string biasCsv(const std::vector<BiasRow>& rows) {
    std::string out = "scene,sampler,spp,seeds,bias,ci95,biased\n";
    for (const BiasRow& r : rows)
        out += csvText(r.scene) + "," + csvText(r.sampler) + "," + std::to_string(r.spp) + "," +
               std::to_string(r.seeds) + "," + optionalNumber(r.bias) + "," +
               optionalNumber(r.ci95) + "," + csvText(r.biased) + "\n";
    return out;
}

}  // namespace pathlab
