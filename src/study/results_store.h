// The study's source of truth: DIR/results.sqlite (tables in
// docs/study-output.md). WAL mode and one transaction per finished cell, so a
// study killed at any moment keeps every cell it finished and nothing else.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

struct sqlite3;

namespace pathlab {

struct CellKey {
    std::string scene, sampler;
    int spp = 0, seed = 0;
    bool operator<(const CellKey& o) const;
    bool operator==(const CellKey& o) const = default;
};

struct CellRow {
    CellKey key;
    double seconds = 0;
    double mse = 0, rmse = 0;
    std::optional<double> relmse, flip, flipMedian, psnr;  // absent when not measured
    int64_t nonFinite = 0;                                 // NaN/Inf samples the renderer discarded
    std::string image;                                     // relative to the study directory
    int width = 0, height = 0, maxDepth = 0, threads = 0;
    std::string gitCommit, finishedAt;
    // MSE over the emitter-edge pixels and the rest (render/emitter_edges.h);
    // absent for a region without pixels and in rows of older studies.
    std::optional<double> mseEdge, mseRest;
    // Relative bias (metrics/bias.h); absent in rows of older studies.
    std::optional<double> bias;
    // Low-frequency error fraction (metrics/error_spectrum.h); absent for a
    // constant error and in rows of older studies.
    std::optional<double> lowFrequencyFraction;
    // An external renderer's cell: the content hash of the file it was
    // measured from (`image` is that file), which --resume compares. Empty
    // for the study's own cells.
    std::string sourceHash;
};

struct ReferenceRow {
    std::string scene, sampler;
    int spp = 0;
    double seconds = 0;
    std::string cacheKey;
    double noiseMse = 0, noiseRelmse = 0;
    double exposure = 0;
    std::string image;
    // The noise floors of the two regions and the number of edge pixels.
    std::optional<double> noiseMseEdge, noiseMseRest;
    std::optional<int64_t> edgePixels;
};

class ResultsStore {
  public:
    // Opens or creates the database and its tables. Throws InputError when the
    // file cannot be opened or is not a study database.
    explicit ResultsStore(const std::string& path, bool readOnly = false);
    ~ResultsStore();
    ResultsStore(const ResultsStore&) = delete;
    ResultsStore& operator=(const ResultsStore&) = delete;

    void putCell(const CellRow& row);  // one transaction; replaces a row with the same key
    std::optional<CellRow> cell(const CellKey& key) const;
    std::vector<CellRow> cells() const;  // in the order they were finished
    int64_t cellCount() const;

    void putReference(const ReferenceRow& row);
    std::vector<ReferenceRow> references() const;

    void setStudyValues(const std::map<std::string, std::string>& values);
    std::map<std::string, std::string> studyValues() const;

    // The study table of an existing database, read without changing the
    // directory: a read-only handle would leave empty -wal and -shm files
    // behind, a read-write one removes them when it closes. Throws InputError
    // when the file cannot be opened or is not a study database.
    static std::map<std::string, std::string> readStudyValues(const std::string& path);

  private:
    void exec(const char* sql) const;
    void addMissingColumns();
    std::vector<CellRow> queryCells(const std::string& where, const CellKey* key) const;

    sqlite3* db_ = nullptr;
    std::string path_;
};

}  // namespace pathlab
