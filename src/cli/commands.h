// Each subcommand lives in its own file and adds itself to the app. A command's
// callback throws InputError for bad input (exit 2) — main() reports it in one
// line — or sets the exit code through `exitCode` when it needs another.
#pragma once

#include <CLI/CLI.hpp>

namespace pathlab::cli {

void addRenderCommand(CLI::App& app);
void addCompareCommand(CLI::App& app);
void addSamplersCommand(CLI::App& app);
void addPointsCommand(CLI::App& app);
void addStudyCommand(CLI::App& app);
void addBenchCommand(CLI::App& app);
void addReportCommand(CLI::App& app);
void addViewCommand(CLI::App& app);

}  // namespace pathlab::cli
