// The study's exports, rewritten from results.sqlite at the end of a run:
// results.csv (one row per cell), results.json and analysis.json.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "study/results_store.h"

namespace pathlab {

// The column names of results.csv, in order (those of the `cells` table).
const std::vector<std::string>& cellColumns();

std::string cellsCsv(const std::vector<CellRow>& cells);

// Writes the three files atomically into `dir`.
void writeExports(const std::filesystem::path& dir, const ResultsStore& store,
                  const nlohmann::ordered_json& analysis);

}  // namespace pathlab
