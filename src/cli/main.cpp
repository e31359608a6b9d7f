// pathlab — a laboratory for sampling strategies in path tracing.
#include <cstdio>
#include <exception>
#include <string>

#include "cli/commands.h"
#include "core/error.h"

int main(int argc, char** argv) {
    CLI::App app{"pathlab — a laboratory for sampling strategies in path tracing", "pathlab"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "pathlab 0.1");
    pathlab::cli::addRenderCommand(app);
    pathlab::cli::addCompareCommand(app);
    pathlab::cli::addSamplersCommand(app);
    pathlab::cli::addPointsCommand(app);
    pathlab::cli::addStudyCommand(app);
    pathlab::cli::addBenchCommand(app);
    pathlab::cli::addReportCommand(app);
    // CLI11 would say "A subcommand is required" for a misspelt command.
    std::string names;
    bool known = false;
    for (const CLI::App* cmd : app.get_subcommands({})) {
        names += (names.empty() ? "" : ", ") + cmd->get_name();
        known = known || (argc > 1 && cmd->get_name() == argv[1]);
    }
    if (argc > 1 && argv[1][0] != '-' && !known) {
        std::fprintf(stderr, "pathlab: error: unknown command '%s' (commands: %s)\n", argv[1],
                     names.c_str());
        return 2;
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        // Usage errors: one line, exit code 2.
        std::fprintf(stderr, "pathlab: error: %s\n", e.what());
        return 2;
    } catch (const pathlab::InputError& e) {
        std::fprintf(stderr, "pathlab: error: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "pathlab: internal error: %s\n", e.what());
        return 1;
    }
    return 0;
}
