// pathlet: the command-line front end. Each subcommand lives in its own cmd_*.cpp.
#include "args.hpp"
#include "build_info.hpp"
#include "commands.hpp"
#include "common/scene_source.hpp"
#include "frames/frames_in_flight.hpp"
#include "graph/graph_model.hpp"
#include "util/text.hpp"
#include <pathlet/gpu_fence.hpp>
#include <pathlet/gpu_scene.hpp>
#include <pathlet/text.hpp>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>

namespace pathlet::cli {
std::vector<Command>& commands() {
    static std::vector<Command> c;
    return c;
}
}  // namespace pathlet::cli

using namespace pathlet::cli;

static void print_overview() {
    std::printf(
        "pathlet %s — render-graph framework for LineAO-lit animated pathlines\n\n"
        "usage: pathlet <command> [arguments] [--help]\n\ncommands:\n",
        PATHLET_VERSION);
    auto cmds = commands();
    std::sort(cmds.begin(), cmds.end(), [](const Command& a, const Command& b) { return a.name < b.name; });
    for (const auto& c : cmds) std::printf("  %-10s %s\n", c.name.c_str(), c.summary.c_str());
    std::printf(
        "\nfirst steps:\n"
        "  pathlet render                       render the built-in aortic-arch phantom with LineAO (variant 1)\n"
        "  pathlet passes                       list the pass plugins found, with their files\n"
        "  pathlet passes --describe lineao     parameters and pins of one pass type\n"
        "  pathlet graph graphs/variant1_lineao.json --plan   execution order, lifetimes, memory\n"
        "\n'pathlet <command> --help' explains each command.\n");
}

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
        print_overview();
        return args.empty() ? 2 : 0;
    }
    if (args[0] == "--version") {
        std::printf("pathlet %s\n%s\n", PATHLET_VERSION, pathlet::build_description().c_str());
        return 0;
    }
    try {  // the environment's GPU settings, before anything runs: a typo is a usage error, never ignored
        pathlet::simulated_gpu_latency();
        pathlet::FramesInFlight::from_env();
        pathlet::GpuScene::default_point_layout();  // PATHLET_POINT_LAYOUT
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 2;
    }
    for (const auto& c : commands()) {
        if (c.name != args[0]) continue;
        try {
            return c.run(std::vector<std::string>(args.begin() + 1, args.end()));
        } catch (const InputError& e) {
            std::fprintf(stderr, "error: %s\n", e.what());
            return 2;
        } catch (const pathlet::DataChoiceError& e) {  // files that do not fit together: the user's choice, as usage
            std::fprintf(stderr, "error: %s\n", e.what());
            return 2;
        } catch (const pathlet::GraphNotFound& e) {
            std::fprintf(stderr, "error: %s\n", e.what());
            return 2;
        } catch (const UsageError& e) {
            std::fprintf(stderr, "pathlet %s: %s\n(see 'pathlet %s --help')\n", c.name.c_str(), e.what(), c.name.c_str());
            return 2;
        } catch (const DeclarationError& e) {  // a bad option declaration: a bug in pathlet
            std::fprintf(stderr, "pathlet %s: internal error: %s\n", c.name.c_str(), e.what());
            return 70;  // EX_SOFTWARE
        } catch (const std::exception& e) {
            std::fprintf(stderr, "pathlet %s: error: %s\n", c.name.c_str(), e.what());
            return 1;
        }
    }
    std::vector<std::string> names;
    for (const auto& c : commands()) names.push_back(c.name);
    std::fprintf(stderr, "error: unknown command '%s'%s; see 'pathlet --help' for the commands\n", args[0].c_str(),
                 pathlet::text::did_you_mean(args[0], names).c_str());
    return 2;
}
