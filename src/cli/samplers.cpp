// `pathlab samplers`: every sampler with a one-line description, its native
// dimension count, whether its seed randomises it, and whether it is
// progressive (its first N samples are the N-spp render).
#include <cstdio>

#include "cli/commands.h"
#include "sampling/registry.h"

namespace pathlab::cli {

void addSamplersCommand(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand("samplers", "List the samplers");
    cmd->callback([] {
        std::printf("%-12s %-11s %-10s %-11s %s\n", "name", "native-dims", "randomized",
                    "progressive", "description");
        for (const SamplerInfo& s : samplerInfos()) {
            const std::string dims =
                s.nativeDimensions == 0 ? "unbounded" : std::to_string(s.nativeDimensions);
            std::printf("%-12s %-11s %-10s %-11s %s\n", s.name.c_str(), dims.c_str(),
                        s.randomized ? "yes" : "no", s.progressive ? "yes" : "no",
                        s.description.c_str());
        }
    });
}

}  // namespace pathlab::cli
