#include "spectral/named_illuminants.h"

#include <map>

#include "spectral/cie_data.h"

namespace pathlab::spectral {
namespace {

const std::map<std::string, PiecewiseLinearSpectrum, std::less<>>& illuminants() {
    static const auto table = [] {
        std::map<std::string, PiecewiseLinearSpectrum, std::less<>> t;
        for (int i = 0; i < cie_data::kIlluminantCount; ++i) {
            const cie_data::TabulatedSpectrum& s = cie_data::kIlluminants[i];
            std::vector<double> lambda, values(s.values, s.values + s.count);
            for (int k = 0; k < s.count; ++k) lambda.push_back(s.first + k * s.step);
            PiecewiseLinearSpectrum spectrum(std::move(lambda), std::move(values));
            spectrum.normaliseToUnitLuminance();
            t.emplace(s.name, std::move(spectrum));
        }
        return t;
    }();
    return table;
}

}  // namespace

const PiecewiseLinearSpectrum* namedIlluminant(std::string_view name) {
    const auto& t = illuminants();
    const auto it = t.find(name);
    return it == t.end() ? nullptr : &it->second;
}

std::string namedIlluminantList() {
    std::string list;
    for (const auto& [name, spectrum] : illuminants()) list += (list.empty() ? "" : ", ") + name;
    return list;
}

}  // namespace pathlab::spectral
