// `pathlab study SPEC.toml | --preset NAME -o DIR [--resume]`: the sampling
// comparison end to end (docs/study.md).
#include <iostream>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "core/error.h"
#include "study/mpi_session.h"
#include "study/mpi_study.h"
#include "study/presets.h"
#include "study/runner.h"
#include "study/spec.h"
#include "study/suite_presets.h"

namespace pathlab::cli {
namespace {

struct StudyArgs {
    std::string spec, preset, output, scenesDir;
    bool resume = false;
    int threads = 0;
};

void requireOneSpecSource(const StudyArgs& a) {
    if (a.spec.empty() == a.preset.empty())
        throw InputError("give either a study spec file or --preset NAME (one of them)");
    if (!a.scenesDir.empty() && !presetTakesPublicScenes(a.preset))
        throw InputError(
            "--scenes-dir adds public pbrt-v4 scenes to --preset suite or "
            "quick-suite, not to " +
            (a.preset.empty() ? std::string("a spec file") : "'" + a.preset + "'"));
}

StudySpec specOf(const StudyArgs& a) {
    if (a.preset.empty()) return loadStudySpec(a.spec);
    StudySpec spec = presetSpec(a.preset);
    if (!a.scenesDir.empty()) addPublicScenes(spec, a.scenesDir, std::cerr);
    return spec;
}

void runStudyCommand(const StudyArgs& a) {
    const StudyOptions options{a.output, a.resume, a.threads};
    const auto loadSpec = [&] {
        requireOneSpecSource(a);
        return specOf(a);
    };
    // Under mpirun or srun: one study across the ranks (docs/cluster.md),
    // which check the options and the spec together, so one rank reports.
    if (launchedByMpiLauncher()) {
        const MpiSession session;
        try {
            runStudyAcrossRanks(loadSpec, options, session);
        } catch (const StoppedWithAnotherRank&) {
            // The rank that failed reports it and sets the job's exit code.
        }
        return;
    }
    requireOneSpecSource(a);
    checkStudyOptions(options);  // before the spec: they are wrong whatever it says
    runStudy(loadSpec(), options);
}

}  // namespace

void addStudyCommand(CLI::App& app) {
    auto args = std::make_shared<StudyArgs>();
    CLI::App* cmd = app.add_subcommand(
        "study", "Render scenes x samplers x spp x seeds against a reference and analyse them");
    cmd->add_option("spec", args->spec, "Study spec (.toml; see docs/study-spec.toml)");
    cmd->add_option("--preset", args->preset,
                    "A built-in study: seed, quick, full, suite or quick-suite");
    cmd->add_option("--scenes-dir", args->scenesDir,
                    "A copy of mmp/pbrt-v4-scenes: the suite presets add the public scenes "
                    "found there (docs/study.md)");
    cmd->add_option("-o,--output", args->output, "Study directory (results, images, analysis)")
        ->required();
    cmd->add_flag("--resume", args->resume,
                  "Continue the study in DIR: skip finished cells, render the rest");
    cmd->add_option("--threads", args->threads,
                    "Worker threads (0 = all cores; under mpirun, per rank: 0 = the host's cores "
                    "shared by its ranks)")
        ->capture_default_str();
    cmd->callback([args] { runStudyCommand(*args); });
}

}  // namespace pathlab::cli
