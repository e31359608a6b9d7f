#include "study/mpi_messages.h"

#include <cstdint>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace pathlab {
namespace {

class ByteWriter {
  public:
    template <typename T>
    void put(const T& value) {
        static_assert(std::is_trivially_copyable_v<T>);
        append(&value, sizeof(T));
    }
    void put(const std::string& s) {
        put(uint64_t(s.size()));
        append(s.data(), s.size());
    }
    void put(const std::optional<double>& v) {
        put(uint8_t(v.has_value()));
        put(v.value_or(0.0));
    }
    void put(const CellKey& key) {
        put(key.scene);
        put(key.sampler);
        put(int32_t(key.spp));
        put(int32_t(key.seed));
    }
    template <typename T>
    void putArray(const T* data, size_t count) {
        put(uint64_t(count));
        append(data, count * sizeof(T));
    }
    std::vector<char> take() { return std::move(bytes_); }

  private:
    // resize and memcpy, not vector::insert: GCC 12 reports a false
    // -Wstringop-overflow on inserting a few bytes (the growth is not seen).
    void append(const void* data, size_t n) {
        const size_t at = bytes_.size();
        bytes_.resize(at + n);
        if (n) std::memcpy(bytes_.data() + at, data, n);
    }
    std::vector<char> bytes_;
};

class ByteReader {
  public:
    explicit ByteReader(const std::vector<char>& bytes) : bytes_(bytes) {}
    template <typename T>
    T get() {
        T value;
        std::memcpy(&value, take(sizeof(T)), sizeof(T));
        return value;
    }
    std::string getString() {
        const auto n = get<uint64_t>();
        const char* p = take(n);
        return std::string(p, p + n);
    }
    std::optional<double> getOptional() {
        const bool has = get<uint8_t>() != 0;
        const double v = get<double>();
        return has ? std::optional<double>(v) : std::nullopt;
    }
    CellKey getKey() {
        CellKey key;
        key.scene = getString();
        key.sampler = getString();
        key.spp = get<int32_t>();
        key.seed = get<int32_t>();
        return key;
    }
    template <typename T>
    std::vector<T> getArray() {
        const auto n = get<uint64_t>();
        std::vector<T> out(n);
        if (n) std::memcpy(out.data(), take(n * sizeof(T)), n * sizeof(T));
        return out;
    }
    bool atEnd() const { return at_ == bytes_.size(); }

  private:
    const char* take(size_t n) {
        if (n > bytes_.size() - at_) throw std::runtime_error("truncated MPI study message");
        const char* p = bytes_.data() + at_;
        at_ += n;
        return p;
    }
    const std::vector<char>& bytes_;
    size_t at_ = 0;
};

}  // namespace

std::vector<char> encodeTask(const RenderTask& task) {
    ByteWriter w;
    w.put(int32_t(task.scene));
    w.put(task.cells.sampler);
    w.put(int32_t(task.cells.seed));
    w.putArray(task.cells.spp.data(), task.cells.spp.size());
    w.put(uint64_t(task.cells.cells.size()));
    for (const CellKey& key : task.cells.cells) w.put(key);
    return w.take();
}

RenderTask decodeTask(const std::vector<char>& bytes) {
    ByteReader r(bytes);
    RenderTask task;
    task.scene = r.get<int32_t>();
    task.cells.sampler = r.getString();
    task.cells.seed = r.get<int32_t>();
    task.cells.spp = r.getArray<int>();
    const auto n = r.get<uint64_t>();
    for (uint64_t i = 0; i < n; ++i) task.cells.cells.push_back(r.getKey());
    return task;
}

std::vector<char> encodeMeasured(const std::vector<study_steps::MeasuredCell>& cells) {
    ByteWriter w;
    w.put(uint64_t(cells.size()));
    for (const study_steps::MeasuredCell& c : cells) {
        const CellMetrics& m = c.metrics;
        w.put(c.key);
        w.put(c.seconds);
        w.put(c.nonFinite);
        w.put(m.mse);
        w.put(m.rmse);
        for (const std::optional<double>* v :
             {&m.relmse, &m.flip, &m.flipMedian, &m.psnr, &m.mseEdge, &m.mseRest, &m.bias,
              &m.lowFrequencyFraction})
            w.put(*v);
    }
    return w.take();
}

std::vector<study_steps::MeasuredCell> decodeMeasured(const std::vector<char>& bytes) {
    ByteReader r(bytes);
    std::vector<study_steps::MeasuredCell> cells(r.get<uint64_t>());
    for (study_steps::MeasuredCell& c : cells) {
        CellMetrics& m = c.metrics;
        c.key = r.getKey();
        c.seconds = r.get<double>();
        c.nonFinite = r.get<uint64_t>();
        m.mse = r.get<double>();
        m.rmse = r.get<double>();
        for (std::optional<double>* v : {&m.relmse, &m.flip, &m.flipMedian, &m.psnr, &m.mseEdge,
                                         &m.mseRest, &m.bias, &m.lowFrequencyFraction})
            *v = r.getOptional();
    }
    return cells;
}

std::vector<char> encodeReferenceImage(const Image& image, float exposure) {
    ByteWriter w;
    w.put(int32_t(image.width));
    w.put(int32_t(image.height));
    w.put(exposure);
    w.putArray(image.rgb.data(), image.rgb.size());
    return w.take();
}

void decodeReferenceImage(const std::vector<char>& bytes, Image& image, float& exposure) {
    ByteReader r(bytes);
    image.width = r.get<int32_t>();
    image.height = r.get<int32_t>();
    exposure = r.get<float>();
    image.rgb = r.getArray<float>();
    if (image.rgb.size() != image.pixelCount() * 3)
        throw std::runtime_error("MPI study message: reference of the wrong size");
}

std::vector<char> encodeRangeTask(const RangeTask& task) {
    ByteWriter w;
    w.put(int32_t(task.scene));
    w.put(int32_t(task.index));
    return w.take();
}

RangeTask decodeRangeTask(const std::vector<char>& bytes) {
    ByteReader r(bytes);
    RangeTask task;
    task.scene = r.get<int32_t>();
    task.index = r.get<int32_t>();
    return task;
}

std::vector<char> encodeRangeResult(int scene, const RangeSums& range,
                                    const std::string& cacheKey) {
    const std::string sums = encodeRangeSums(range, cacheKey);
    std::vector<char> bytes(sizeof(int32_t) + sums.size());
    const int32_t s = scene;
    std::memcpy(bytes.data(), &s, sizeof s);
    std::memcpy(bytes.data() + sizeof s, sums.data(), sums.size());
    return bytes;
}

RangeSums decodeRangeResult(const std::vector<char>& bytes, int& scene,
                            const std::vector<std::string>& cacheKeys) {
    ByteReader r(bytes);
    scene = r.get<int32_t>();
    if (scene < 0 || size_t(scene) >= cacheKeys.size())
        throw std::runtime_error("MPI study message: sums of an unknown scene");
    const std::string_view sums(bytes.data() + sizeof(int32_t), bytes.size() - sizeof(int32_t));
    return decodeRangeSums(sums, cacheKeys[size_t(scene)]);
}

}  // namespace pathlab
