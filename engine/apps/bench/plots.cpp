#include "plots.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <vector>

#ifndef PATHLET_PYTHON
#define PATHLET_PYTHON "python3"
#endif
#ifndef PATHLET_INSTALL_PYTHONDIR
#define PATHLET_INSTALL_PYTHONDIR "lib/python3/site-packages"
#endif

namespace pathlet::cli::bench {

std::string write_matplotlib_plots(const std::string& dir) {
    namespace fs = std::filesystem;
    std::error_code ec;
    // build/bin/pathlet -> build/python (the package next to the module); installed (or in a
    // bundle), PREFIX/bin/pathlet -> PREFIX/lib/python3.X/site-packages.
    const fs::path prefix = fs::read_symlink("/proc/self/exe", ec).parent_path().parent_path();
    std::string pythonpath;
    for (const fs::path& tree : {prefix / "python", prefix / PATHLET_INSTALL_PYTHONDIR}) {
        if (ec || !fs::is_regular_file(tree / "pathlet" / "plot.py")) continue;
        pythonpath = tree.string();
        if (const char* old = std::getenv("PYTHONPATH"); old && *old) pythonpath += ":" + std::string(old);
        break;
    }
    const std::string python = PATHLET_PYTHON, results = dir + "/results.json";
    std::vector<std::string> args = {python, "-m", "pathlet.plot", results, "--out", dir};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const pid_t pid = fork();
    if (pid < 0) return "cannot start " + python;
    if (pid == 0) {
        if (!pythonpath.empty()) setenv("PYTHONPATH", pythonpath.c_str(), 1);
        execvp(argv[0], argv.data());
        _exit(127);
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) return "lost the plot process";
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return "";
    if (WIFEXITED(status) && WEXITSTATUS(status) == 127) return python + " not found (install python3-matplotlib)";
    return python + " -m pathlet.plot failed (needs python3-matplotlib and the pathlet package; see above)";
}

}  // namespace pathlet::cli::bench
