// Subcommand registry: each cmd_*.cpp registers itself with PATHLET_COMMAND, so adding a
// subcommand never touches main.cpp. A command returns the process exit code:
// 0 success, 1 failure of the work (bad data, GL error), 2 bad usage.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace pathlet::cli {

using CommandFn = std::function<int(const std::vector<std::string>& args)>;

struct Command {
    std::string name, summary;
    CommandFn run;
};

std::vector<Command>& commands();

struct CommandRegistrar {
    CommandRegistrar(std::string name, std::string summary, CommandFn fn) {
        commands().push_back({std::move(name), std::move(summary), std::move(fn)});
    }
};

}  // namespace pathlet::cli

#define PATHLET_CONCAT2(a, b) a##b
#define PATHLET_CONCAT(a, b) PATHLET_CONCAT2(a, b)
#define PATHLET_COMMAND(name, summary, fn) \
    static ::pathlet::cli::CommandRegistrar PATHLET_CONCAT(pathlet_cmd_, __LINE__)(name, summary, fn)
