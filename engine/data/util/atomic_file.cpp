#include "atomic_file.hpp"

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <unistd.h>

namespace fs = std::filesystem;

namespace pathlet {

std::string temp_path_for(const std::string& path) {
    static std::atomic<int> counter{0};
    fs::path p(path);
    std::string name = "." + p.stem().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
                       std::to_string(counter++) + p.extension().string();
    return (p.parent_path() / name).string();
}

void remove_stale_temps(const std::string& dir) {
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec)) {
        const std::string name = e.path().filename().string();
        const size_t at = name.find(".tmp-");
        if (name.empty() || name[0] != '.' || at == std::string::npos) continue;
        const long pid = std::atol(name.c_str() + at + 5);
        if (pid <= 0 || pid == long(::getpid())) continue;
        if (::kill(pid_t(pid), 0) == 0 || errno != ESRCH) continue;  // still running (or not ours to judge)
        fs::remove(e.path(), ec);
    }
}

void commit_temp(const std::string& tmp, const std::string& path) {
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw std::runtime_error(path + ": cannot move finished file into place from " + tmp + ": " + ec.message());
    }
}

void write_file_atomic(const std::string& path, const std::function<void(std::ostream&)>& fill) {
    std::string tmp = temp_path_for(path);
    try {
        {
            std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
            if (!out) throw std::runtime_error(path + ": cannot open for writing");
            fill(out);
            out.flush();
            if (!out) throw std::runtime_error(path + ": write failed (disk full?)");
        }
        commit_temp(tmp, path);
    } catch (...) {
        std::error_code ec;
        fs::remove(tmp, ec);
        throw;
    }
}

void write_file_atomic(const std::string& path, std::string_view bytes) {
    write_file_atomic(path, [&](std::ostream& out) { out.write(bytes.data(), std::streamsize(bytes.size())); });
}

}  // namespace pathlet
