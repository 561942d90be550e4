// Runs the pathlet binary (or any command) as a user would: exit code, stdout and stderr.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

// A shell command's exit code, stdout and stderr (files under the test's binary dir, one pair a run).
struct CliRun {
    int code = -1;
    std::string out, err;
};

inline CliRun run_command(const std::string& command) {
    fs::path dir = fs::path(PATHLET_TEST_BINARY_DIR) / "cli_runs";
    fs::create_directories(dir);
    // ctest runs tests in parallel processes: each run gets its own files.
    static int counter = 0;  // inline function: one counter per process
    std::string tag = std::to_string(::getpid()) + "_" + std::to_string(counter++);
    std::string out = (dir / ("out_" + tag + ".txt")).string(), err = (dir / ("err_" + tag + ".txt")).string();
    int status = std::system((command + " >" + out + " 2>" + err + " </dev/null").c_str());
    CliRun r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128;
    auto slurp = [](const std::string& p) {
        std::ifstream in(p);
        std::stringstream s;
        s << in.rdbuf();
        return s.str();
    };
    r.out = slurp(out);
    r.err = slurp(err);
    return r;
}

// The pathlet command with `args` (and environment assignments `env` before it).
inline CliRun pathlet_cli(const std::string& args, const std::string& env = "") {
    return run_command(env + (env.empty() ? "" : " ") + std::string(PATHLET_CLI) + " " + args);
}

inline std::string src(const std::string& rel) { return std::string(PATHLET_SOURCE_DIR) + "/" + rel; }

