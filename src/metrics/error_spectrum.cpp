#include "metrics/error_spectrum.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>

#include "core/atomic_file.h"
#include "core/error.h"
#include "metrics/error_spectrum_plot.h"

namespace pathlab {
namespace {

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

}  // namespace

std::vector<double> signedErrorField(const Image& reference, const Image& test) {
    std::vector<double> error(reference.pixelCount());
    for (size_t i = 0; i < error.size(); ++i) {
        const float* r = &reference.rgb[3 * i];
        const float* t = &test.rgb[3 * i];
        error[i] = ((double(t[0]) - r[0]) + (double(t[1]) - r[1]) + (double(t[2]) - r[2])) / 3.0;
    }
    return error;
}

RadialPowerSpectrum errorSpectrum(const Image& reference, const Image& test) {
    return radialPeriodogram(signedErrorField(reference, test), reference.width, reference.height);
}

double lowFrequencyErrorFraction(const RadialPowerSpectrum& spectrum) {
    return spectrum.lowFrequencyFraction();
}

double lowFrequencyErrorFraction(const Image& reference, const Image& test) {
    return errorSpectrum(reference, test).lowFrequencyFraction();
}

std::string errorSpectrumCsv(const RadialPowerSpectrum& spectrum) {
    std::string csv = "frequency,power\n";
    char line[64];
    for (size_t r = 0; r < spectrum.power.size(); ++r) {
        std::snprintf(line, sizeof line, "%.17g,%.17g\n", spectrum.frequency[r], spectrum.power[r]);
        csv += line;
    }
    return csv;
}

void checkErrorSpectrumPath(const std::string& path) {
    const std::string ext = lowerExtension(path);
    if (ext != ".csv" && ext != ".png")
        throw InputError("--error-spectrum must name a .csv or .png file, got '" + path + "'");
    checkDirectoryWritable(path);
}

void writeErrorSpectrum(const std::string& path, const RadialPowerSpectrum& spectrum) {
    if (lowerExtension(path) == ".png")
        writeImage(path, errorSpectrumPlot(spectrum));
    else
        writeFileAtomic(path, errorSpectrumCsv(spectrum));
}

}  // namespace pathlab
