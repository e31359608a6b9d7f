// `pathlab report DIR`: the study's web page and figures, in DIR/report/.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "report/report_writer.h"

namespace pathlab::cli {

void addReportCommand(CLI::App& app) {
    auto dir = std::make_shared<std::string>();
    CLI::App* cmd = app.add_subcommand(
        "report",
        "Write DIR/report/index.html (opens from disk) and the figures as SVG and PNG under "
        "DIR/report/figures/ for a study directory");
    cmd->add_option("dir", *dir, "Study directory written by `pathlab study`")->required();
    cmd->callback([dir] {
        ReportOptions options;
        options.studyDir = *dir;
        std::error_code ec;
        // The gallery runs this very binary's `points` command.
        options.pathlabBinary = std::filesystem::read_symlink("/proc/self/exe", ec);
        const std::filesystem::path index = writeReport(options);
        std::printf("%s\n", index.string().c_str());
    });
}

}  // namespace pathlab::cli
