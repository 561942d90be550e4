// Runs the pathlet binary as a user would: exit code, stdout and stderr (for CLI tests).
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

struct CliRun {
    int code = -1;
    std::string out, err;
};

inline CliRun pathlet_cli(const std::string& args, const std::string& env = "") {
    fs::path dir = fs::path(PATHLET_TEST_BINARY_DIR) / "cli_runs";
    fs::create_directories(dir);
    // ctest runs tests in parallel processes: each run gets its own files.
    static int counter = 0;  // inline function: one counter per process
    std::string tag = std::to_string(::getpid()) + "_" + std::to_string(counter++);
    std::string out = (dir / ("out_" + tag + ".txt")).string(), err = (dir / ("err_" + tag + ".txt")).string();
    std::string cmd = env + (env.empty() ? "" : " ") + std::string(PATHLET_CLI) + " " + args + " >" + out + " 2>" + err + " </dev/null";
    int status = std::system(cmd.c_str());
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

inline std::string src(const std::string& rel) { return std::string(PATHLET_SOURCE_DIR) + "/" + rel; }

