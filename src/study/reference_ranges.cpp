#include "study/reference_ranges.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <type_traits>

#include "core/atomic_file.h"
#include "render/renderer.h"
#include "study/cell_metrics.h"

namespace pathlab {
namespace fs = std::filesystem;
namespace {

// Bumped whenever the bytes below change: older files are then rendered again.
constexpr std::string_view kMagic = "pathlab-range-sums-1\n";

template <typename T>
void put(std::string& out, const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

template <typename T>
void putArray(std::string& out, const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    put(out, uint64_t(v.size()));
    if (!v.empty()) out.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

class Reader {
  public:
    explicit Reader(std::string_view bytes) : bytes_(bytes) {}
    const char* take(size_t n) {
        if (n > bytes_.size() - at_) throw std::runtime_error("truncated sample-range sums");
        const char* p = bytes_.data() + at_;
        at_ += n;
        return p;
    }
    template <typename T>
    T get() {
        T value;
        std::memcpy(&value, take(sizeof(T)), sizeof(T));
        return value;
    }
    template <typename T>
    std::vector<T> getArray() {
        const auto n = get<uint64_t>();
        if (n > (bytes_.size() - at_) / sizeof(T))
            throw std::runtime_error("truncated sample-range sums");
        std::vector<T> out(n);
        if (n) std::memcpy(static_cast<void*>(out.data()), take(n * sizeof(T)), n * sizeof(T));
        return out;
    }
    bool atEnd() const { return at_ == bytes_.size(); }

  private:
    std::string_view bytes_;
    size_t at_ = 0;
};

std::string readWholeFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return {};
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace

std::vector<SampleRange> referenceRanges(int spp, int count) {
    // Automatic: the fewest ranges of whole batches that keeps them at most
    // kMaxReferenceRanges, ⌈spp / max⌉ rounded up to a batch. Asked for:
    // ⌈spp / count⌉ each, batches or not.
    const int ranges = count > 0 ? count : kMaxReferenceRanges;
    const int perRange = std::max(1, (spp + ranges - 1) / ranges);
    const int size = count > 0 ? perRange
                               : (perRange + kMinReferenceRangeSpp - 1) / kMinReferenceRangeSpp *
                                     kMinReferenceRangeSpp;
    std::vector<SampleRange> out;
    for (int first = 0; first < spp; first += size)
        out.push_back({first, std::min(spp, first + size)});
    return out;
}

std::string encodeRangeSums(const RangeSums& r, const std::string& cacheKey) {
    std::string out(kMagic);
    put(out, uint64_t(cacheKey.size()));
    out += cacheKey;
    put(out, int32_t(r.index));
    put(out, int32_t(r.sums.first));
    put(out, int32_t(r.sums.spp));
    put(out, r.seconds);
    static_assert(sizeof(PlainSums) == 6 * sizeof(double), "no padding in the file");
    static_assert(sizeof(WeightedSums) == 15 * sizeof(double), "no padding in the file");
    putArray(out, r.sums.plain);
    putArray(out, r.sums.weighted);
    return out;
}

RangeSums decodeRangeSums(std::string_view bytes, const std::string& cacheKey) {
    Reader in(bytes);
    if (std::string_view(in.take(kMagic.size()), kMagic.size()) != kMagic)
        throw std::runtime_error("not sample-range sums");
    const auto keySize = in.get<uint64_t>();
    if (std::string_view(in.take(keySize), keySize) != cacheKey)
        throw std::runtime_error("sample-range sums of another reference");
    RangeSums r;
    r.index = in.get<int32_t>();
    r.sums.first = in.get<int32_t>();
    r.sums.spp = in.get<int32_t>();
    r.seconds = in.get<double>();
    r.sums.plain = in.getArray<PlainSums>();
    r.sums.weighted = in.getArray<WeightedSums>();
    if (!in.atEnd()) throw std::runtime_error("sample-range sums followed by other bytes");
    return r;
}

ReferenceRangeFiles::ReferenceRangeFiles(fs::path directory, std::string cacheKey, int spp,
                                         int count)
    : directory_(std::move(directory)),
      cacheKey_(std::move(cacheKey)),
      ranges_(referenceRanges(spp, count)) {}

fs::path ReferenceRangeFiles::path(int index) const {
    return directory_ / (cacheKey_ + ".range-" + std::to_string(index) + "-of-" +
                         std::to_string(ranges_.size()) + ".sums");
}

std::vector<int> ReferenceRangeFiles::missing() const {
    std::vector<int> out;
    std::error_code ec;
    for (int i = 0; i < int(ranges_.size()); ++i)
        if (!fs::is_regular_file(path(i), ec)) out.push_back(i);
    return out;
}

std::optional<RangeSums> ReferenceRangeFiles::load(int index) const {
    try {
        RangeSums r = decodeRangeSums(readWholeFile(path(index)), cacheKey_);
        const SampleRange& want = ranges_.at(size_t(index));
        if (r.index != index || r.sums.first != want.first || r.sums.spp != want.count())
            return std::nullopt;
        return r;
    } catch (const std::exception&) {
        return std::nullopt;
    }
}

void ReferenceRangeFiles::save(const RangeSums& range) const {
    std::error_code ec;
    fs::create_directories(directory_, ec);
    writeFileAtomic(path(range.index).string(), encodeRangeSums(range, cacheKey_));
}

void ReferenceRangeFiles::removeAll() const {
    std::error_code ec;
    for (int i = 0; i < int(ranges_.size()); ++i) fs::remove(path(i), ec);
}

ReferenceRangeFiles referenceRangeFiles(const ReferenceCache& cache, const std::string& cacheKey,
                                        const StudySpec& spec) {
    return ReferenceRangeFiles(cache.directory(), cacheKey, spec.reference.spp,
                               spec.reference.ranges);
}

// The reference's settings: its sampler is made for all its spp, whichever
// range is rendered, so that each range draws the whole render's samples.
RangeSums renderReferenceRange(const RenderScene& scene, const StudySpec& spec, int threads,
                               int index, RenderControl* control) {
    RenderSettings s = studyRenderSettings(spec, threads);
    s.control = control;
    s.sampler = spec.reference.sampler;
    s.samplesPerPixel = spec.reference.spp;
    s.seed = spec.reference.seed;
    s.sampleRange = referenceRanges(spec.reference.spp, spec.reference.ranges).at(size_t(index));
    RangeSums r;
    r.index = index;
    s.resume = &r.sums;
    r.seconds = render(scene, s).stats.seconds;
    return r;
}

Reference mergeReferenceRanges(const RenderScene& scene, const StudySpec& spec,
                               const ReferenceRangeFiles& files,
                               const std::function<RangeSums(int)>& renderMissing,
                               const std::vector<uint8_t>& edgeMask) {
    RunningSums total;
    Reference ref;
    for (int i = 0; i < int(files.ranges().size()); ++i) {
        std::optional<RangeSums> range = files.load(i);
        if (!range) range = renderMissing(i);
        addRunningSums(total, range->sums);
        ref.seconds += range->seconds;
    }
    RenderSettings s = studyRenderSettings(spec, 0);
    RenderOutput out = imageOfRunningSums(scene, s, total);
    ref.noise = referenceNoise(out.image, out.varianceOfMean, &edgeMask);
    ref.exposure = viewingExposure(out.image);
    ref.image = std::move(out.image);
    ref.cacheKey = files.cacheKey();
    ref.edgePixels = std::count(edgeMask.begin(), edgeMask.end(), uint8_t(1));
    return ref;
}

}  // namespace pathlab
