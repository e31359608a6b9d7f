// The study's screen-space error: every cell's low-frequency error fraction in
// the results store (also in a database begun before the column existed), and
// seed 0's error spectrum beside its images, as `pathlab compare` computes it.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <cmath>
#include <filesystem>

#include "metrics/error_spectrum.h"
#include "study_test_util.h"

namespace pathlab {
namespace {
namespace fs = std::filesystem;
using testing::runPathlab;

// A database with the cells table as it was before the column (its bias and
// source_hash already there) opens; its rows have no fraction, new rows keep one.
TEST(StudySpectrum, OlderDatabaseGainsTheColumn) {
    const auto dir = testing::scratchDirectory("spectrum-old");
    const std::string path = (dir / "results.sqlite").string();
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
    const char* old = R"sql(
CREATE TABLE cells (
  scene TEXT NOT NULL, sampler TEXT NOT NULL, spp INTEGER NOT NULL, seed INTEGER NOT NULL,
  seconds REAL, mse REAL, rmse REAL, relmse REAL, flip REAL, flip_median REAL, psnr REAL,
  nonfinite INTEGER, image TEXT, width INTEGER, height INTEGER, max_depth INTEGER,
  threads INTEGER, git_commit TEXT, finished_at TEXT, mse_edge REAL, mse_rest REAL, bias REAL,
  source_hash TEXT, PRIMARY KEY (scene, sampler, spp, seed));
INSERT INTO cells (scene, sampler, spp, seed, mse, bias) VALUES ('plane', 'sobol', 1, 0, 0.3, 0.01);
)sql";
    ASSERT_EQ(sqlite3_exec(db, old, nullptr, nullptr, nullptr), SQLITE_OK);
    sqlite3_close(db);

    ResultsStore store(path);
    const auto before = store.cell({"plane", "sobol", 1, 0});
    ASSERT_TRUE(before);
    EXPECT_EQ(before->bias, 0.01);
    EXPECT_FALSE(before->lowFrequencyFraction.has_value());
    CellRow row;
    row.key = {"plane", "zsobol", 1, 0};
    row.lowFrequencyFraction = 0.0125;
    store.putCell(row);
    EXPECT_EQ(store.cell(row.key)->lowFrequencyFraction, 0.0125);
}

TEST(StudySpectrum, CellsKeepTheFractionAndSeedZeroItsSpectrum) {
    const auto dir = testing::scratchDirectory("study-spectrum");
    testing::usePrivateCache(dir);
    const auto spec =
        testing::writeSpec(dir, "s.toml",
                           "name = \"spectrum\"\nscenes = [\"cornell-box\"]\n"
                           "samplers = [\"independent\", \"zsobol\"]\nspp = [1, 4]\nseeds = 2\n"
                           "resolution = [40, 32]\nmax_depth = 3\n[reference]\nspp = 32\n");
    const fs::path out = dir / "study";
    const auto r = runPathlab("study " + spec.string() + " -o " + out.string(), dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto cells = testing::readCells(out);
    ASSERT_EQ(cells.size(), 8u);
    const Image reference = readImage((out / "references" / "cornell-box.exr").string());
    for (const CellRow& c : cells) {
        SCOPED_TRACE(c.image);
        const Image image = readImage((out / c.image).string());
        const RadialPowerSpectrum expected = errorSpectrum(reference, image);
        ASSERT_TRUE(c.lowFrequencyFraction.has_value());
        EXPECT_EQ(*c.lowFrequencyFraction, expected.lowFrequencyFraction());
        const fs::path csv = out / (c.image.substr(0, c.image.size() - 4) + "-spectrum.csv");
        if (c.key.seed == 0)
            EXPECT_EQ(testing::slurpFile(csv), errorSpectrumCsv(expected));
        else
            EXPECT_FALSE(fs::exists(csv));
    }
    const std::string header = testing::slurpFile(out / "results.csv").substr(0, 400);
    EXPECT_NE(header.find(",low_frequency_fraction,"), std::string::npos) << header;
    fs::remove_all(dir);
}

}  // namespace
}  // namespace pathlab
