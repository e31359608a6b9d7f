// A study's reference in sample ranges (study/reference_ranges.h): the
// ranges depend on the reference's spp only and cover it in whole batches;
// a range's file comes back bit for bit and only as the range it is; a study
// uses the ranges an earlier run saved, and removes them once merged.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>

#include "core/error.h"
#include "scene/loader.h"
#include "study/reference_ranges.h"
#include "study/runner.h"
#include "study_test_util.h"

namespace pathlab {
namespace {
namespace fs = std::filesystem;

TEST(ReferenceRanges, CoverTheSamplesInWholeBatches) {
    for (int spp : {1, 63, 64, 65, 256, 1000, 4096, 65536, 1 << 24}) {
        const std::vector<SampleRange> ranges = referenceRanges(spp);
        ASSERT_FALSE(ranges.empty());
        EXPECT_LE(int(ranges.size()), kMaxReferenceRanges) << spp;
        EXPECT_EQ(ranges.front().first, 0);
        EXPECT_EQ(ranges.back().end, spp);
        for (size_t i = 0; i < ranges.size(); ++i) {
            EXPECT_GT(ranges[i].count(), 0) << spp;
            EXPECT_EQ(ranges[i].first % kMinReferenceRangeSpp, 0) << spp;
            if (i > 0) {
                EXPECT_EQ(ranges[i].first, ranges[i - 1].end) << spp;
            }
            // Equal ranges but the last, which may be shorter.
            if (i + 1 < ranges.size()) {
                EXPECT_EQ(ranges[i].count(), ranges[0].count()) << spp;
            }
        }
    }
    EXPECT_EQ(referenceRanges(4096).size(), 16u);  // one per rank of 16
}

// `[reference] ranges = N`: N ranges of ⌈spp / N⌉ samples, batches or not,
// fewer only where the last ones would hold none.
TEST(ReferenceRanges, AskedForCountSplitsIntoThatManyEqualRanges) {
    struct Case {
        int spp, count;
        std::vector<int> sizes;
    };
    for (const Case& c :
         {Case{4096, 64, std::vector<int>(64, 64)}, Case{4096, 256, std::vector<int>(256, 16)},
          Case{1000, 3, {334, 334, 332}}, Case{10, 4, {3, 3, 3, 1}},
          Case{10, 6, {2, 2, 2, 2, 2}},  // a sixth would be empty
          Case{7, 7, std::vector<int>(7, 1)}, Case{256, 1, {256}}}) {
        const std::vector<SampleRange> ranges = referenceRanges(c.spp, c.count);
        std::vector<int> sizes;
        int next = 0;
        for (const SampleRange& r : ranges) {
            EXPECT_EQ(r.first, next) << c.spp << " in " << c.count;
            next = r.end;
            sizes.push_back(r.count());
        }
        EXPECT_EQ(next, c.spp);
        EXPECT_EQ(sizes, c.sizes) << c.spp << " in " << c.count;
    }
    // Asking for the automatic count's own split changes nothing but the key.
    EXPECT_EQ(referenceRanges(4096, 16).size(), referenceRanges(4096).size());
}

RangeSums someSums(int index, int first, int spp, size_t pixels) {
    RangeSums r;
    r.index = index;
    r.seconds = 0.1 + 0.2;
    r.sums.first = first;
    r.sums.spp = spp;
    r.sums.plain.resize(pixels);
    for (size_t i = 0; i < pixels; ++i)
        for (int c = 0; c < 3; ++c) r.sums.plain[i].sum[c] = 1.0 / 3.0 + double(i * 3 + c);
    return r;
}

TEST(ReferenceRanges, RangeFilesComeBackBitForBitAndOnlyAsTheirRange) {
    const auto dir = testing::scratchDirectory("range-files");
    const ReferenceRangeFiles files(dir, "k3y", 256);  // 4 ranges of 64
    ASSERT_EQ(files.ranges().size(), 4u);
    EXPECT_EQ(files.missing(), (std::vector<int>{0, 1, 2, 3}));
    const RangeSums saved = someSums(2, 128, 64, 5);
    files.save(saved);
    EXPECT_EQ(files.missing(), (std::vector<int>{0, 1, 3}));
    const std::optional<RangeSums> back = files.load(2);
    ASSERT_TRUE(back);
    EXPECT_EQ(std::memcmp(back->sums.plain.data(), saved.sums.plain.data(), 5 * sizeof(PlainSums)),
              0);
    EXPECT_EQ(back->seconds, saved.seconds);
    EXPECT_EQ(back->sums.first, 128);
    // Another reference's bytes, or another range's, are refused.
    const std::string bytes = encodeRangeSums(saved, "k3y");
    EXPECT_THROW(decodeRangeSums(bytes, "other"), std::runtime_error);
    EXPECT_THROW(decodeRangeSums(bytes.substr(0, bytes.size() - 1), "k3y"), std::runtime_error);
    files.save(someSums(1, 0, 64, 5));  // says range 1, holds range 0's samples
    EXPECT_FALSE(files.load(1));
    EXPECT_FALSE(files.load(0));  // no file
    files.removeAll();
    EXPECT_EQ(files.missing().size(), 4u);
    fs::remove_all(dir);
}

Image studyReference(const fs::path& study) {
    return readImage((study / "references/cornell-box.exr").string());
}

bool anyRangeFile(const fs::path& cache) {
    for (const auto& entry : fs::recursive_directory_iterator(cache))
        if (entry.path().extension() == ".sums") return true;
    return false;
}

// A range saved by an earlier run is used as it is (its recorded seconds
// show), and the reference is the same bits as one rendered in one go.
TEST(ReferenceRanges, StudyUsesSavedRangesAndRemovesThem) {
    const auto dir = testing::scratchDirectory("study-ranges");
    const StudySpec spec =
        loadStudySpec(testing::writeSpec(dir, "tiny.toml", testing::tinySpec()).string());
    testing::usePrivateCache(dir / "fresh");
    runStudy(spec, {dir / "fresh/study", false, 2});
    EXPECT_FALSE(anyRangeFile(dir / "fresh/cache"));

    const fs::path cache = testing::usePrivateCache(dir / "saved");
    const SceneDescription scene = loadScene("cornell-box");
    const std::string key = referenceCacheKey(scene, spec.scenes.at(0), spec);
    const RenderScene renderScene(loadScene("cornell-box"));
    RangeSums range = renderReferenceRange(renderScene, spec, 1, 2);
    range.seconds = 1000;  // marks it
    referenceRangeFiles(ReferenceCache::standard(), key, spec).save(range);
    runStudy(spec, {dir / "saved/study", false, 2});
    EXPECT_FALSE(anyRangeFile(cache));

    EXPECT_TRUE(studyReference(dir / "fresh/study").rgb == studyReference(dir / "saved/study").rgb);
    const auto rows =
        ResultsStore((dir / "saved/study/results.sqlite").string(), true).references();
    ASSERT_EQ(rows.size(), 1u);
    EXPECT_GE(rows[0].seconds, 1000);
    fs::remove_all(dir);
}

// A spec's range count: its own cache key and range files, the same samples
// added in another grouping (equal to rounding), and a study resumed with
// another count is refused as a changed spec.
TEST(ReferenceRanges, SpecRangeCountIsInTheKeyAndTheFilesNotInTheSamples) {
    const auto dir = testing::scratchDirectory("study-range-count");
    const StudySpec automatic =
        loadStudySpec(testing::writeSpec(dir, "auto.toml", testing::tinySpec()).string());
    const StudySpec seven = loadStudySpec(
        testing::writeSpec(dir, "seven.toml", testing::tinySpec() + "ranges = 7\n").string());
    EXPECT_EQ(automatic.reference.ranges, 0);
    ASSERT_EQ(seven.reference.ranges, 7);
    const SceneDescription scene = loadScene("cornell-box");
    const std::string key = referenceCacheKey(scene, seven.scenes.at(0), seven);
    EXPECT_NE(key, referenceCacheKey(scene, automatic.scenes.at(0), automatic));
    const ReferenceRangeFiles files = referenceRangeFiles(ReferenceCache::standard(), key, seven);
    ASSERT_EQ(files.ranges().size(), 7u);  // 256 = 6 × 37 + 34
    EXPECT_EQ(files.ranges().back().count(), 34);
    EXPECT_NE(files.path(6).filename().string().find(".range-6-of-7.sums"), std::string::npos);

    testing::usePrivateCache(dir / "cache");
    runStudy(automatic, {dir / "auto", false, 2});
    runStudy(seven, {dir / "seven", false, 2});
    const Image a = studyReference(dir / "auto"), b = studyReference(dir / "seven");
    ASSERT_EQ(a.rgb.size(), b.rgb.size());
    // The same samples grouped otherwise: double sums that may differ in their
    // last bits, which the float image rarely keeps.
    for (size_t i = 0; i < a.rgb.size(); ++i)
        ASSERT_NEAR(a.rgb[i], b.rgb[i], 1e-5f * (1 + std::abs(a.rgb[i]))) << i;
    EXPECT_THROW(runStudy(seven, {dir / "auto", true, 2}), InputError);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace pathlab
