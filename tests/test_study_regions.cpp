// The study's error split by region (emitter edge / rest): what the database
// keeps, how an older database gains the columns, and that a study's two
// region MSEs add up to the whole image's.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "render/emitter_edges.h"
#include "scene/builtin_scenes.h"
#include "study_test_util.h"

namespace pathlab {
namespace {
namespace fs = std::filesystem;
using testing::runPathlab;

CellRow regionRow(const std::string& sampler, std::optional<double> edge,
                  std::optional<double> rest) {
    CellRow c;
    c.key = {"cornell-box", sampler, 4, 0};
    c.mse = 0.5;
    c.mseEdge = edge;
    c.mseRest = rest;
    return c;
}

TEST(StudyRegions, StoreKeepsTheRegionColumns) {
    const auto dir = testing::scratchDirectory("regions-store");
    ResultsStore store((dir / "results.sqlite").string());
    store.putCell(regionRow("halton", 2.5, 0.125));
    store.putCell(regionRow("sobol", std::nullopt, 0.25));  // no edge pixels
    store.putReference(
        {"cornell-box", "independent", 64, 1.0, "k", 0.01, 0.02, 0.0, "r.exr", 0.75, 0.001, 112});
    const auto halton = store.cell({"cornell-box", "halton", 4, 0});
    ASSERT_TRUE(halton && halton->mseEdge && halton->mseRest);
    EXPECT_EQ(*halton->mseEdge, 2.5);
    EXPECT_EQ(*halton->mseRest, 0.125);
    const auto sobol = store.cell({"cornell-box", "sobol", 4, 0});
    ASSERT_TRUE(sobol);
    EXPECT_FALSE(sobol->mseEdge.has_value());
    const auto refs = store.references();
    ASSERT_EQ(refs.size(), 1u);
    EXPECT_EQ(refs[0].noiseMseEdge, 0.75);
    EXPECT_EQ(refs[0].noiseMseRest, 0.001);
    EXPECT_EQ(refs[0].edgePixels, 112);
}

// A database written before the region columns existed (its tables exactly as
// they were) is opened, read and written on.
TEST(StudyRegions, OlderDatabaseGainsTheColumns) {
    const auto dir = testing::scratchDirectory("regions-old");
    const std::string path = (dir / "results.sqlite").string();
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
    const char* old = R"sql(
CREATE TABLE cells (
  scene TEXT NOT NULL, sampler TEXT NOT NULL, spp INTEGER NOT NULL, seed INTEGER NOT NULL,
  seconds REAL, mse REAL, rmse REAL, relmse REAL, flip REAL, flip_median REAL, psnr REAL,
  nonfinite INTEGER, image TEXT, width INTEGER, height INTEGER, max_depth INTEGER,
  threads INTEGER, git_commit TEXT, finished_at TEXT,
  PRIMARY KEY (scene, sampler, spp, seed));
CREATE TABLE "references" (
  scene TEXT PRIMARY KEY, sampler TEXT, spp INTEGER, seconds REAL, cache_key TEXT,
  noise_mse REAL, noise_relmse REAL, exposure REAL, image TEXT);
CREATE TABLE study (key TEXT PRIMARY KEY, value TEXT);
INSERT INTO cells (scene, sampler, spp, seed, mse) VALUES ('cornell-box', 'halton', 1, 0, 0.3);
INSERT INTO "references" (scene, noise_mse) VALUES ('cornell-box', 0.01);
)sql";
    ASSERT_EQ(sqlite3_exec(db, old, nullptr, nullptr, nullptr), SQLITE_OK);
    sqlite3_close(db);

    ResultsStore store(path);
    const auto cells = store.cells();
    ASSERT_EQ(cells.size(), 1u);
    EXPECT_EQ(cells[0].mse, 0.3);
    EXPECT_FALSE(cells[0].mseEdge.has_value());
    EXPECT_FALSE(store.references().at(0).edgePixels.has_value());
    store.putCell(regionRow("pmj02", 1.0, 0.5));
    EXPECT_EQ(store.cell({"cornell-box", "pmj02", 4, 0})->mseRest, 0.5);
}

TEST(StudyRegions, RegionMsesAddUpToTheImagesMse) {
    const auto dir = testing::scratchDirectory("regions-study");
    testing::usePrivateCache(dir);
    const auto spec = testing::writeSpec(dir, "s.toml", testing::tinySpec());
    ASSERT_EQ(runPathlab("study " + spec.string() + " -o " + (dir / "out").string(), dir).exitCode,
              0);
    ResultsStore store((dir / "out" / "results.sqlite").string(), /*readOnly=*/true);
    const auto refs = store.references();
    ASSERT_EQ(refs.size(), 1u);
    ASSERT_TRUE(refs[0].edgePixels && refs[0].noiseMseEdge && refs[0].noiseMseRest);
    const double edge = double(*refs[0].edgePixels), pixels = 32.0 * 32.0;
    // The light is in view: some pixels, a small part of the image.
    EXPECT_GT(edge, 0);
    EXPECT_LT(edge, pixels / 10);
    // The reference's floors weighted by region size give its whole floor.
    EXPECT_NEAR((*refs[0].noiseMseEdge * edge + *refs[0].noiseMseRest * (pixels - edge)) / pixels,
                refs[0].noiseMse, 1e-9 * refs[0].noiseMse);
    const auto cells = store.cells();
    ASSERT_FALSE(cells.empty());
    for (const CellRow& c : cells) {
        ASSERT_TRUE(c.mseEdge && c.mseRest) << c.key.sampler;
        EXPECT_NEAR((*c.mseEdge * edge + *c.mseRest * (pixels - edge)) / pixels, c.mse,
                    1e-9 * c.mse);
    }
    // The report's picture of the region: the reference with the edge in cyan.
    const Image marked = readImage((dir / "out" / "references" / "cornell-box-edge.png").string());
    const Image plain = readImage((dir / "out" / "references" / "cornell-box.png").string());
    const auto mask = emitterEdgePixels(RenderScene(cornellBoxScene()), {32, 32});
    int differ = 0;
    for (size_t i = 0; i < mask.size(); ++i) {
        const int x = int(i % 32), y = int(i / 32);
        const Vec3f m = marked.at(x, y), p = plain.at(x, y);
        if (mask[i]) {
            EXPECT_TRUE(m.x == 0 && m.y == 1 && m.z == 1) << x << "," << y;
        } else {
            differ += m.x != p.x || m.y != p.y || m.z != p.z;
        }
    }
    EXPECT_EQ(differ, 0);
    // The analysis reports the split, with independent's share of the error.
    const auto analysis = nlohmann::json::parse(testing::slurpFile(dir / "out" / "analysis.json"));
    const auto& regions = analysis["scenes"]["cornell-box"]["regions"];
    EXPECT_EQ(regions["edge_pixels"].get<int64_t>(), *refs[0].edgePixels);
    const double share = regions["independent_edge_share"]["16"].get<double>();
    EXPECT_GT(share, 0.0);
    EXPECT_LT(share, 1.0);
    EXPECT_FALSE(analysis["scenes"]["cornell-box"]["samplers"]["halton-rd"]["mse_ratio_by_region"]
                         ["rest"]["16"]
                             .is_null());
}

}  // namespace
}  // namespace pathlab
