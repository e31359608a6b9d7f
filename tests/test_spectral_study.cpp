// A spectral study end to end: a tiny study with `spectral = true` (and hero
// wavelengths) runs, records its colour mode, and its report says so.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "cli_runner.h"
#include "core/paths.h"
#include "spectral/rgb_spectrum_table.h"
#include "study/results_store.h"
#include "study_test_util.h"

namespace pathlab {
namespace {
namespace fs = std::filesystem;
using testing::runPathlab;

TEST(SpectralStudy, TinyStudyRunsAndItsReportSaysSpectral) {
    // The study gets a private cache; the RGB-to-spectrum table, which takes
    // seconds to make, is copied there from the ordinary cache.
    spectral::defaultRgbToSpectrumTable();
    const fs::path table =
        cacheDirectory() /
        ("rgb-to-spectrum-srgb-" + std::to_string(spectral::kRgbToSpectrumResolution) + ".bin");
    const auto dir = testing::scratchDirectory("spectral-study");
    const fs::path cache = testing::usePrivateCache(dir);
    if (fs::exists(table)) fs::copy_file(table, cache / table.filename());
    const auto spec = testing::writeSpec(dir, "spectral.toml",
                                         "name = \"spectral\"\n"
                                         "scenes = [\"cornell-box\"]\n"
                                         "samplers = [\"independent\", \"sobol-owen\"]\n"
                                         "spp = [1, 4]\n"
                                         "resolution = [16, 16]\n"
                                         "spectral = true\n"
                                         "wavelengths = \"hero\"\n"
                                         "[reference]\n"
                                         "spp = 32\n");
    const auto out = dir / "study";
    auto r = runPathlab("study " + spec.string() + " -o " + out.string(), dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::vector<CellRow> cells = testing::readCells(out);
    EXPECT_EQ(cells.size(), 2u * 2);  // samplers × spp
    for (const CellRow& c : cells) {
        ASSERT_TRUE(c.relmse) << c.key.sampler;
        EXPECT_TRUE(std::isfinite(*c.relmse) && *c.relmse > 0) << c.key.sampler;
    }
    {
        ResultsStore store((out / "results.sqlite").string(), /*readOnly=*/true);
        const auto values = store.studyValues();
        EXPECT_EQ(values.at("spectral"), "true");
        EXPECT_EQ(values.at("wavelengths"), "hero");
    }
    r = runPathlab("report " + out.string(), dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string index = testing::slurpFile(out / "report/index.html");
    EXPECT_NE(index.find("<dt>colour</dt><dd>spectral (hero wavelengths)</dd>"), std::string::npos);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace pathlab
