#include "atomic_file.hpp"

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <map>
#include <mutex>
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace pathlet {

namespace {
// Temps this process is writing, each held under an flock: the kernel drops the lock when the
// process dies (even by SIGKILL), so a temp nobody holds is a leftover, whatever its PID says
// (PIDs wrap and are reused within seconds on a busy machine).
std::mutex g_temps_mutex;
std::map<std::string, int> g_temps;

void release_temp(const std::string& tmp) {
    std::lock_guard<std::mutex> lock(g_temps_mutex);
    auto it = g_temps.find(tmp);
    if (it == g_temps.end()) return;
    ::close(it->second);  // also releases the flock
    g_temps.erase(it);
}
}  // namespace

std::string temp_path_for(const std::string& path) {
    static std::atomic<int> counter{0};
    fs::path p(path);
    std::string name = "." + p.stem().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
                       std::to_string(counter++) + p.extension().string();
    std::string tmp = (p.parent_path() / name).string();
    int fd = ::open(tmp.c_str(), O_CREAT | O_WRONLY | O_CLOEXEC, 0644);
    if (fd >= 0) {
        ::flock(fd, LOCK_EX);
        std::lock_guard<std::mutex> lock(g_temps_mutex);
        g_temps[tmp] = fd;
    }  // (a folder that cannot take it fails with a clear error when the writer opens it)
    return tmp;
}

std::string temp_dir_in(const std::string& dir, const std::string& name) {
    static std::atomic<int> counter{0};
    const std::string tmp =
        (fs::path(dir) / ("." + name + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + ".d")).string();
    std::error_code ec;
    fs::create_directory(tmp, ec);
    if (ec) throw std::runtime_error(tmp + ": cannot create a temporary folder: " + ec.message());
    int fd = ::open(tmp.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) {
        fs::remove(tmp, ec);
        throw std::runtime_error(tmp + ": cannot open the temporary folder");
    }
    ::flock(fd, LOCK_EX);  // held while we live: remove_stale_temps of another render leaves it
    std::lock_guard<std::mutex> lock(g_temps_mutex);
    g_temps[tmp] = fd;
    return tmp;
}

void discard_temp(const std::string& tmp) {
    std::error_code ec;
    fs::remove_all(tmp, ec);
    release_temp(tmp);
}

void remove_stale_temps(const std::string& dir) {
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec)) {
        const std::string name = e.path().filename().string();
        if (name.empty() || name[0] != '.' || name.find(".tmp-") == std::string::npos) continue;
        {
            std::lock_guard<std::mutex> lock(g_temps_mutex);
            if (g_temps.count(e.path().string())) continue;  // ours, being written
        }
        int fd = ::open(e.path().c_str(), O_RDONLY | O_CLOEXEC);
        if (fd < 0) continue;
        const bool orphan = ::flock(fd, LOCK_EX | LOCK_NB) == 0;  // its writer is gone
        if (orphan) fs::remove_all(e.path(), ec);  // a temp folder goes with its content
        ::close(fd);
    }
}

void commit_temp(const std::string& tmp, const std::string& path) {
    std::error_code ec;
    fs::rename(tmp, path, ec);
    release_temp(tmp);
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
        release_temp(tmp);
        throw;
    }
}

void write_file_atomic(const std::string& path, std::string_view bytes) {
    write_file_atomic(path, [&](std::ostream& out) { out.write(bytes.data(), std::streamsize(bytes.size())); });
}

}  // namespace pathlet
