#include "study/results_store.h"

#include <sqlite3.h>

#include <cerrno>
#include <stdexcept>
#include <tuple>

#include "core/atomic_file.h"
#include "core/error.h"

namespace pathlab {
namespace {

constexpr const char* kSchema = R"sql(
CREATE TABLE IF NOT EXISTS cells (
  scene TEXT NOT NULL, sampler TEXT NOT NULL, spp INTEGER NOT NULL, seed INTEGER NOT NULL,
  seconds REAL, mse REAL, rmse REAL, relmse REAL, flip REAL, flip_median REAL, psnr REAL,
  nonfinite INTEGER, image TEXT, width INTEGER, height INTEGER, max_depth INTEGER,
  threads INTEGER, git_commit TEXT, finished_at TEXT, mse_edge REAL, mse_rest REAL, bias REAL, source_hash TEXT,
  low_frequency_fraction REAL,
  PRIMARY KEY (scene, sampler, spp, seed));
CREATE TABLE IF NOT EXISTS "references" (
  scene TEXT PRIMARY KEY, sampler TEXT, spp INTEGER, seconds REAL, cache_key TEXT,
  noise_mse REAL, noise_relmse REAL, exposure REAL, image TEXT,
  noise_mse_edge REAL, noise_mse_rest REAL, edge_pixels INTEGER);
CREATE TABLE IF NOT EXISTS study (key TEXT PRIMARY KEY, value TEXT);
)sql";

constexpr const char* kCellColumns =
    "scene, sampler, spp, seed, seconds, mse, rmse, relmse, flip, flip_median, psnr, "
    "nonfinite, image, width, height, max_depth, threads, git_commit, finished_at, mse_edge, "
    "mse_rest, bias, source_hash, low_frequency_fraction";

// Columns added since the first schema, with their tables: a study begun by an
// older pathlab gains them (NULL in its old rows) when it is resumed.
struct AddedColumn {
    const char* table;
    const char* column;
    const char* type;
};
constexpr AddedColumn kAddedColumns[] = {{"cells", "mse_edge", "REAL"},
                                         {"cells", "mse_rest", "REAL"},
                                         {"cells", "bias", "REAL"},
                                         {"cells", "source_hash", "TEXT"},
                                         {"cells", "low_frequency_fraction", "REAL"},
                                         {"references", "noise_mse_edge", "REAL"},
                                         {"references", "noise_mse_rest", "REAL"},
                                         {"references", "edge_pixels", "INTEGER"}};

// Throws for SQLite's last error on `db` (the database file `path`): a full
// disk or a file that cannot be written is the user's to fix (InputError,
// one line naming the file), anything else is an internal failure.
[[noreturn]] void throwSqliteError(sqlite3* db, const std::string& path) {
    const int code = sqlite3_extended_errcode(db);
    const std::string what = sqlite3_errmsg(db);
    switch (code & 0xff) {
        case SQLITE_FULL:
            throw InputError(writeErrorMessage(path, ENOSPC));
        case SQLITE_IOERR:
            if (sqlite3_system_errno(db) != 0)
                throw InputError(writeErrorMessage(path, sqlite3_system_errno(db)));
            throw InputError("cannot write '" + path + "': " + what);
        case SQLITE_READONLY:
        case SQLITE_CANTOPEN:
        case SQLITE_PERM:
            throw InputError("cannot write '" + path + "': " + what);
        default:
            throw std::runtime_error("SQLite: " + what);
    }
}

// A prepared statement that finalises itself; binds by 1-based position.
class Statement {
  public:
    Statement(sqlite3* db, const std::string& sql, const std::string& path) : db_(db), path_(path) {
        if (sqlite3_prepare_v2(db, sql.c_str(), -1, &stmt_, nullptr) != SQLITE_OK)
            throwSqliteError(db, path);
    }
    ~Statement() { sqlite3_finalize(stmt_); }
    Statement(const Statement&) = delete;
    Statement& operator=(const Statement&) = delete;

    void bind(int i, const std::string& v) {
        sqlite3_bind_text(stmt_, i, v.c_str(), int(v.size()), SQLITE_TRANSIENT);
    }
    void bind(int i, int64_t v) { sqlite3_bind_int64(stmt_, i, v); }
    void bind(int i, double v) { sqlite3_bind_double(stmt_, i, v); }
    void bind(int i, const std::optional<double>& v) {
        if (v)
            bind(i, *v);
        else
            bindNull(i);
    }
    void bindNull(int i) { sqlite3_bind_null(stmt_, i); }
    // True while there is a row to read.
    bool step() {
        const int rc = sqlite3_step(stmt_);
        if (rc == SQLITE_ROW) return true;
        if (rc == SQLITE_DONE) return false;
        throwSqliteError(db_, path_);
    }
    std::string text(int i) const {
        const auto* p = sqlite3_column_text(stmt_, i);
        return p ? reinterpret_cast<const char*>(p) : "";
    }
    int64_t integer(int i) const { return sqlite3_column_int64(stmt_, i); }
    double real(int i) const { return sqlite3_column_double(stmt_, i); }
    std::optional<double> optionalReal(int i) const {
        if (sqlite3_column_type(stmt_, i) == SQLITE_NULL) return std::nullopt;
        return real(i);
    }

  private:
    sqlite3* db_;
    const std::string& path_;
    sqlite3_stmt* stmt_ = nullptr;
};

CellRow readCell(const Statement& s) {
    CellRow r;
    r.key = {s.text(0), s.text(1), int(s.integer(2)), int(s.integer(3))};
    r.seconds = s.real(4);
    r.mse = s.real(5);
    r.rmse = s.real(6);
    r.relmse = s.optionalReal(7);
    r.flip = s.optionalReal(8);
    r.flipMedian = s.optionalReal(9);
    r.psnr = s.optionalReal(10);
    r.nonFinite = s.integer(11);
    r.image = s.text(12);
    r.width = int(s.integer(13));
    r.height = int(s.integer(14));
    r.maxDepth = int(s.integer(15));
    r.threads = int(s.integer(16));
    r.gitCommit = s.text(17);
    r.finishedAt = s.text(18);
    r.mseEdge = s.optionalReal(19);
    r.mseRest = s.optionalReal(20);
    r.bias = s.optionalReal(21);
    r.sourceHash = s.text(22);
    r.lowFrequencyFraction = s.optionalReal(23);
    return r;
}

}  // namespace

bool CellKey::operator<(const CellKey& o) const {
    return std::tie(scene, sampler, spp, seed) < std::tie(o.scene, o.sampler, o.spp, o.seed);
}

ResultsStore::ResultsStore(const std::string& path, bool readOnly) : path_(path) {
    const int flags = readOnly ? SQLITE_OPEN_READONLY : SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE;
    if (sqlite3_open_v2(path.c_str(), &db_, flags, nullptr) != SQLITE_OK) {
        const std::string why = db_ ? sqlite3_errmsg(db_) : "out of memory";
        sqlite3_close(db_);
        throw InputError("cannot open study database '" + path + "': " + why);
    }
    // Another process (a report, a test) may read while we write.
    sqlite3_busy_timeout(db_, 10000);
    if (readOnly) return;
    try {
        // WAL: a commit is one append, and a kill mid-write leaves the last
        // committed state readable. FULL: each committed cell survives even
        // a power cut, at the price of one fsync per cell.
        exec("PRAGMA journal_mode=WAL");
        exec("PRAGMA synchronous=FULL");
        exec(kSchema);
        addMissingColumns();
    } catch (const InputError&) {
        sqlite3_close(db_);
        throw;  // a full disk, a file that cannot be written
    } catch (const std::exception& e) {
        sqlite3_close(db_);
        throw InputError("'" + path + "' is not a usable study database: " + e.what());
    }
}

ResultsStore::~ResultsStore() {
    sqlite3_close(db_);
}

void ResultsStore::addMissingColumns() {
    for (const AddedColumn& c : kAddedColumns) {
        Statement info(db_, std::string("PRAGMA table_info(\"") + c.table + "\")", path_);
        bool present = false;
        while (info.step()) present = present || info.text(1) == c.column;
        if (present) continue;
        exec((std::string("ALTER TABLE \"") + c.table + "\" ADD COLUMN " + c.column + " " + c.type)
                 .c_str());
    }
}

void ResultsStore::exec(const char* sql) const {
    if (sqlite3_exec(db_, sql, nullptr, nullptr, nullptr) != SQLITE_OK)
        throwSqliteError(db_, path_);
}

void ResultsStore::putCell(const CellRow& r) {
    Statement s(db_,
                std::string("INSERT OR REPLACE INTO cells (") + kCellColumns +
                    ") VALUES (?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?)",
                path_);
    s.bind(1, r.key.scene);
    s.bind(2, r.key.sampler);
    s.bind(3, int64_t(r.key.spp));
    s.bind(4, int64_t(r.key.seed));
    s.bind(5, r.seconds);
    s.bind(6, r.mse);
    s.bind(7, r.rmse);
    s.bind(8, r.relmse);
    s.bind(9, r.flip);
    s.bind(10, r.flipMedian);
    s.bind(11, r.psnr);
    s.bind(12, r.nonFinite);
    s.bind(13, r.image);
    s.bind(14, int64_t(r.width));
    s.bind(15, int64_t(r.height));
    s.bind(16, int64_t(r.maxDepth));
    s.bind(17, int64_t(r.threads));
    s.bind(18, r.gitCommit);
    s.bind(19, r.finishedAt);
    s.bind(20, r.mseEdge);
    s.bind(21, r.mseRest);
    s.bind(22, r.bias);
    if (r.sourceHash.empty())
        s.bindNull(23);
    else
        s.bind(23, r.sourceHash);
    s.bind(24, r.lowFrequencyFraction);
    // A single statement is its own transaction: the row is there whole or not at all.
    s.step();
}

std::vector<CellRow> ResultsStore::queryCells(const std::string& where, const CellKey* key) const {
    Statement s(db_, std::string("SELECT ") + kCellColumns + " FROM cells " + where, path_);
    if (key) {
        s.bind(1, key->scene);
        s.bind(2, key->sampler);
        s.bind(3, int64_t(key->spp));
        s.bind(4, int64_t(key->seed));
    }
    std::vector<CellRow> out;
    while (s.step()) out.push_back(readCell(s));
    return out;
}

std::optional<CellRow> ResultsStore::cell(const CellKey& key) const {
    auto rows = queryCells("WHERE scene=? AND sampler=? AND spp=? AND seed=?", &key);
    if (rows.empty()) return std::nullopt;
    return rows.front();
}

std::vector<CellRow> ResultsStore::cells() const {
    return queryCells("ORDER BY rowid", nullptr);
}

int64_t ResultsStore::cellCount() const {
    Statement s(db_, "SELECT COUNT(*) FROM cells", path_);
    s.step();
    return s.integer(0);
}

void ResultsStore::putReference(const ReferenceRow& r) {
    Statement s(db_,
                "INSERT OR REPLACE INTO \"references\" (scene, sampler, spp, seconds, cache_key, "
                "noise_mse, noise_relmse, exposure, image, noise_mse_edge, noise_mse_rest, "
                "edge_pixels) VALUES (?,?,?,?,?,?,?,?,?,?,?,?)",
                path_);
    s.bind(1, r.scene);
    s.bind(2, r.sampler);
    s.bind(3, int64_t(r.spp));
    s.bind(4, r.seconds);
    s.bind(5, r.cacheKey);
    s.bind(6, r.noiseMse);
    s.bind(7, r.noiseRelmse);
    s.bind(8, r.exposure);
    s.bind(9, r.image);
    s.bind(10, r.noiseMseEdge);
    s.bind(11, r.noiseMseRest);
    if (r.edgePixels)
        s.bind(12, *r.edgePixels);
    else
        s.bindNull(12);
    s.step();
}

std::vector<ReferenceRow> ResultsStore::references() const {
    Statement s(db_,
                "SELECT scene, sampler, spp, seconds, cache_key, noise_mse, noise_relmse, "
                "exposure, image, noise_mse_edge, noise_mse_rest, edge_pixels "
                "FROM \"references\" ORDER BY rowid",
                path_);
    std::vector<ReferenceRow> out;
    while (s.step()) {
        std::optional<int64_t> edgePixels;
        if (s.optionalReal(11)) edgePixels = s.integer(11);
        out.push_back({s.text(0), s.text(1), int(s.integer(2)), s.real(3), s.text(4), s.real(5),
                       s.real(6), s.real(7), s.text(8), s.optionalReal(9), s.optionalReal(10),
                       edgePixels});
    }
    return out;
}

void ResultsStore::setStudyValues(const std::map<std::string, std::string>& values) {
    exec("BEGIN IMMEDIATE");
    try {
        for (const auto& [k, v] : values) {
            Statement s(db_, "INSERT OR REPLACE INTO study (key, value) VALUES (?, ?)", path_);
            s.bind(1, k);
            s.bind(2, v);
            s.step();
        }
        exec("COMMIT");
    } catch (...) {
        // SQLite may have rolled back already (a full disk does that).
        if (!sqlite3_get_autocommit(db_)) sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
        throw;
    }
}

std::map<std::string, std::string> ResultsStore::readStudyValues(const std::string& path) {
    sqlite3* db = nullptr;
    if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READWRITE, nullptr) != SQLITE_OK) {
        const std::string why = db ? sqlite3_errmsg(db) : "out of memory";
        sqlite3_close(db);
        throw InputError("cannot open study database '" + path + "': " + why);
    }
    sqlite3_busy_timeout(db, 10000);
    std::map<std::string, std::string> out;
    try {
        // A run killed between creating the file and its first commit leaves
        // a database without tables: it records no study yet, so nothing to
        // compare (the resumed run creates the schema as a new one would).
        bool hasTable = false;
        {
            Statement t(db, "SELECT COUNT(*) FROM sqlite_master WHERE name = 'study'", path);
            hasTable = t.step() && t.integer(0) > 0;
        }
        if (hasTable) {
            Statement s(db, "SELECT key, value FROM study", path);
            while (s.step()) out[s.text(0)] = s.text(1);
        }
    } catch (const std::exception& e) {
        sqlite3_close(db);
        throw InputError("'" + path + "' is not a usable study database: " + e.what());
    }
    sqlite3_close(db);
    return out;
}

std::map<std::string, std::string> ResultsStore::studyValues() const {
    Statement s(db_, "SELECT key, value FROM study", path_);
    std::map<std::string, std::string> out;
    while (s.step()) out[s.text(0)] = s.text(1);
    return out;
}

}  // namespace pathlab
