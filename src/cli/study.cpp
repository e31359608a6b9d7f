// `pathlab study SPEC.toml | --preset NAME -o DIR [--resume]`: the sampling
// comparison end to end (docs/study.md).
#include <memory>
#include <string>

#include "cli/commands.h"
#include "core/error.h"
#include "study/presets.h"
#include "study/runner.h"
#include "study/spec.h"

namespace pathlab::cli {
namespace {

struct StudyArgs {
    std::string spec, preset, output;
    bool resume = false;
    int threads = 0;
};

void runStudyCommand(const StudyArgs& a) {
    if (a.spec.empty() == a.preset.empty())
        throw InputError("give either a study spec file or --preset NAME (one of them)");
    const StudyOptions options{a.output, a.resume, a.threads};
    checkStudyOptions(options);  // before the spec: they are wrong whatever it says
    const StudySpec spec = a.preset.empty() ? loadStudySpec(a.spec) : presetSpec(a.preset);
    runStudy(spec, options);
}

}  // namespace

void addStudyCommand(CLI::App& app) {
    auto args = std::make_shared<StudyArgs>();
    CLI::App* cmd = app.add_subcommand(
        "study", "Render scenes x samplers x spp x seeds against a reference and analyse them");
    cmd->add_option("spec", args->spec, "Study spec (.toml; see docs/study-spec.toml)");
    cmd->add_option("--preset", args->preset, "A built-in study: seed, quick or full");
    cmd->add_option("-o,--output", args->output, "Study directory (results, images, analysis)")
        ->required();
    cmd->add_flag("--resume", args->resume,
                  "Continue the study in DIR: skip finished cells, render the rest");
    cmd->add_option("--threads", args->threads, "Worker threads (0 = all cores)")
        ->capture_default_str();
    cmd->callback([args] { runStudyCommand(*args); });
}

}  // namespace pathlab::cli
