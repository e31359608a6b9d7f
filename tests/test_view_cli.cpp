// `pathlab view` on the command line: bad input is one line and exit code 2
// before serving (also a port already in use); Ctrl-C (SIGINT) and POST
// /api/stop end the server with exit code 0.
#include <gtest/gtest.h>
#include <httplib.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <string>

#include "cli_runner.h"

namespace pathlab {
namespace {

using testing::runPathlab;

class ViewCli : public ::testing::Test {
  protected:
    void SetUp() override { dir = testing::scratchDirectory("view-cli"); }
    void TearDown() override { std::filesystem::remove_all(dir); }
    std::filesystem::path dir;
};

TEST_F(ViewCli, BadInputIsOneLineAndExitCode2) {
    const std::pair<const char*, const char*> cases[] = {
        {"--scene cornell-box --sampler nope", "nope"},
        {"--scene cornell-box --compare nope2", "nope2"},
        {"--scene no-such-scene.json", "no-such-scene.json"},
        {"--scene cornell-box --size 0x5", "size"},
        {"--scene cornell-box --port 70000", "port"},
        {"--scene cornell-box --max-spp 0", "max-spp"},
        {"--scene cornell-box --equal fast", "--equal"},
    };
    for (const auto& [args, named] : cases) {
        const auto r = runPathlab(std::string("view ") + args, dir);
        EXPECT_EQ(r.exitCode, 2) << args;
        EXPECT_EQ(r.errLines(), 1) << args << ": " << r.err;
        EXPECT_NE(r.err.find(named), std::string::npos) << args << ": " << r.err;
        EXPECT_TRUE(r.out.empty()) << "no URL for a server that never served";
    }
}

TEST_F(ViewCli, PortInUseIsRefused) {
    httplib::Server other;
    const int port = other.bind_to_any_port("127.0.0.1");
    ASSERT_GT(port, 0);
    const auto r =
        runPathlab("view --scene cornell-box --size 16x16 --port " + std::to_string(port), dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.errLines(), 1) << r.err;
    EXPECT_NE(r.err.find(std::to_string(port)), std::string::npos) << r.err;
}

// Starts `pathlab view` on a free port; returns its pid and the port it printed.
std::pair<pid_t, int> startView() {
    int fds[2];
    if (pipe(fds) != 0) return {-1, 0};
    const pid_t pid = fork();
    if (pid == 0) {
        dup2(fds[1], 1);
        close(fds[0]), close(fds[1]);
        execl(PATHLAB_BINARY, PATHLAB_BINARY, "view", "--scene", "cornell-box", "--size", "16x16",
              "--port", "0", "--threads", "1", static_cast<char*>(nullptr));
        _exit(127);
    }
    close(fds[1]);
    std::string line;
    char c;
    while (read(fds[0], &c, 1) == 1 && c != '\n') line += c;
    close(fds[0]);
    const size_t colon = line.rfind(':');
    const int port = colon == std::string::npos ? 0 : std::atoi(line.c_str() + colon + 1);
    return {pid, port};
}

int exitCodeOf(pid_t pid) {
    int status = 0;
    waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST_F(ViewCli, CtrlCStopsCleanly) {
    const auto [pid, port] = startView();
    ASSERT_GT(pid, 0);
    ASSERT_GT(port, 0);
    httplib::Client client("127.0.0.1", port);
    const auto res = client.Get("/api/status");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 200);
    kill(pid, SIGINT);
    EXPECT_EQ(exitCodeOf(pid), 0);
}

TEST_F(ViewCli, ApiStopEndsTheProgram) {
    const auto [pid, port] = startView();
    ASSERT_GT(pid, 0);
    ASSERT_GT(port, 0);
    httplib::Client client("127.0.0.1", port);
    const auto res = client.Post("/api/stop", "", "application/json");
    ASSERT_TRUE(res);
    EXPECT_EQ(exitCodeOf(pid), 0);
}

}  // namespace
}  // namespace pathlab
