// `pathlab samplers`: every sampler with a one-line description, its native
// dimension count, whether its seed randomises it, and whether it is
// progressive (its first N samples are the N-spp render).
#include <algorithm>
#include <cstdio>

#include "cli/commands.h"
#include "sampling/registry.h"

namespace pathlab::cli {

void addSamplersCommand(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand("samplers", "List the samplers");
    cmd->callback([] {
        int width = 4;  // the name column fits the longest name
        for (const SamplerInfo& s : samplerInfos()) width = std::max(width, int(s.name.size()));
        std::printf("%-*s %-11s %-10s %-11s %s\n", width, "name", "native-dims", "randomized",
                    "progressive", "description");
        for (const SamplerInfo& s : samplerInfos()) {
            const std::string dims =
                s.nativeDimensions == 0 ? "unbounded" : std::to_string(s.nativeDimensions);
            std::printf("%-*s %-11s %-10s %-11s %s\n", width, s.name.c_str(), dims.c_str(),
                        s.randomized ? "yes" : "no", s.progressive ? "yes" : "no",
                        s.description.c_str());
        }
    });
}

}  // namespace pathlab::cli
