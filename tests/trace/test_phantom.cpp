// The synthetic aortic-arch phantom: sizes, bounds, time span, determinism, cache.
#include "phantom/phantom.hpp"
#include "util/cache_dir.hpp"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <stdexcept>

using namespace pathlet;

namespace {

const Scene& small_phantom() {
    static const Scene s = phantom::make_phantom(phantom::phantom_preset("small"));
    return s;
}

}  // namespace

TEST(Phantom, SmallPresetHasAFewHundredLinesInsideTheArch) {
    const Scene& s = small_phantom();
    EXPECT_GE(s.lines.line_count(), 150u);
    EXPECT_LE(s.lines.line_count(), 1000u);
    EXPECT_EQ(s.lines.time.size(), s.lines.point_count());
    EXPECT_EQ(s.lines.velocity.size(), s.lines.point_count());
    glm::vec3 lo(1e9f), hi(-1e9f);
    float tmin = 1e9f, tmax = -1e9f;
    for (size_t i = 0; i < s.lines.point_count(); ++i) {
        lo = glm::min(lo, s.lines.position[i]), hi = glm::max(hi, s.lines.position[i]);
        tmin = std::min(tmin, s.lines.time[i]), tmax = std::max(tmax, s.lines.time[i]);
    }
    // Root at the origin, arch up to z ~ 80 mm, descending aorta down to z ~ -100 mm.
    EXPECT_GT(lo.z, -115.0f);
    EXPECT_LT(lo.z, -80.0f);
    EXPECT_GT(hi.z, 60.0f);
    EXPECT_LT(hi.z, 95.0f);
    EXPECT_GE(tmin, 0.0f);
    EXPECT_LE(tmax, 4.0f);
    EXPECT_GT(tmax - tmin, 3.0f);  // releases spread over the whole window
    for (const auto& l : s.lines.lines) {
        ASSERT_GE(l.count, 2u);
        for (uint32_t i = l.first + 1; i < l.first + l.count; ++i) ASSERT_GE(s.lines.time[i], s.lines.time[i - 1]);
    }
    EXPECT_EQ(s.lines.units, (Units{"mm", "s", "mm/s"}));  // the phantom knows its units
    ASSERT_TRUE(s.mesh.has_value());
    EXPECT_GT(s.mesh->index.size() / 3, 2000u);
    EXPECT_EQ(s.mesh->normal.size(), s.mesh->position.size());
}

TEST(Phantom, SmallPresetIsDeterministic) {
    auto o = phantom::phantom_preset("small");
    o.trace.threads = 1;
    const Scene again = phantom::make_phantom(o);
    EXPECT_EQ(again.lines.position, small_phantom().lines.position);
    EXPECT_EQ(again.lines.time, small_phantom().lines.time);
    EXPECT_EQ(again.mesh->index, small_phantom().mesh->index);
}

TEST(Phantom, FieldHasParabolicFlowAndAMask) {
    const auto f = phantom::make_phantom_field(phantom::phantom_preset("small"));
    EXPECT_GT(f.vessel_voxels(), 1000u);
    // The root cross-section: fastest in the middle, ~2x the 150 mm/s mean.
    const glm::vec3 v = f.frames[0][f.grid.index(f.grid.nearest({0.0f, 0.0f, 20.0f}))];
    EXPECT_NEAR(v.z, 300.0f, 30.0f);
    EXPECT_THROW(phantom::phantom_preset("huge"), std::invalid_argument);
}

TEST(Phantom, CachePathAndReuse) {
    const auto dir = std::filesystem::path(PATHLET_TEST_BINARY_DIR) / "phantom-cache";
    std::filesystem::remove_all(dir);
    setenv("XDG_CACHE_HOME", dir.c_str(), 1);
    const std::string path = phantom::phantom_cache_path("small");
    EXPECT_EQ(path, (dir / "pathlet" / "phantom-small-v2.pathlet").string());
    const Scene made = phantom::load_or_make_phantom("small");
    EXPECT_TRUE(std::filesystem::exists(path));
    EXPECT_TRUE(std::filesystem::exists(dir / "pathlet" / "phantom-small-v2.glb"));
    const Scene loaded = phantom::load_or_make_phantom("small");
    EXPECT_EQ(loaded.source, path);  // came from the cache
    EXPECT_EQ(loaded.lines.units, made.lines.units);
    EXPECT_EQ(loaded.lines.position, made.lines.position);
    EXPECT_EQ(loaded.lines.lines.size(), made.lines.lines.size());
    ASSERT_TRUE(loaded.mesh.has_value());
    EXPECT_EQ(loaded.mesh->index.size(), made.mesh->index.size());
    unsetenv("XDG_CACHE_HOME");
}

// The cache folder: a relative XDG_CACHE_HOME is ignored (the XDG spec), and without HOME the
// folder is the user's own in the temporary directory (pathlet-cache-UID, 0700), refused when
// what is there is a link or open to other users, never a shared predictable /tmp/pathlet-cache.
TEST(Phantom, CacheFolderIsTheUsersOwnAndARelativeXdgCacheHomeIsIgnored) {
    struct Env {  // sets a variable for the test, restores it after
        std::string name;
        std::optional<std::string> was;
        Env(std::string n, const char* v) : name(std::move(n)) {
            if (const char* w = std::getenv(name.c_str())) was = w;
            if (v) setenv(name.c_str(), v, 1);
            else unsetenv(name.c_str());
        }
        ~Env() {
            if (was) setenv(name.c_str(), was->c_str(), 1);
            else unsetenv(name.c_str());
        }
    };
    namespace fs = std::filesystem;
    const fs::path tmp = fs::path(PATHLET_TEST_BINARY_DIR) / "cache-dir-tmp";
    fs::remove_all(tmp);
    fs::create_directories(tmp);
    {
        Env xdg("XDG_CACHE_HOME", "relative/cache"), home("HOME", tmp.c_str());
        EXPECT_EQ(cache_dir(), (tmp / ".cache" / "pathlet").string()) << "a relative XDG_CACHE_HOME is ignored";
    }
    Env xdg("XDG_CACHE_HOME", nullptr), home("HOME", nullptr), tmpdir("TMPDIR", tmp.c_str());
    const fs::path own = tmp / ("pathlet-cache-" + std::to_string(getuid()));
    EXPECT_EQ(cache_dir(), own.string());
    struct stat st {};
    ASSERT_EQ(lstat(own.c_str(), &st), 0) << "made when missing";
    EXPECT_TRUE(S_ISDIR(st.st_mode));
    EXPECT_EQ(st.st_mode & 0777, 0700u);
    EXPECT_EQ(cache_dir(), own.string()) << "and used again as it is";
    auto refused = [&](const char* what) {
        try {
            cache_dir();
            ADD_FAILURE() << what << ": used";
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find(own.string()), std::string::npos) << e.what();
        }
    };
    chmod(own.c_str(), 0777);
    refused("a folder others may write");
    fs::remove_all(own);
    fs::create_directories(tmp / "elsewhere");
    fs::create_directory_symlink(tmp / "elsewhere", own);
    refused("a link planted where the folder goes");
    fs::remove_all(tmp);
}

// The study phantom as generated (the first run) and as cached (every later run) is one data
// set: the tracer emits no point whose float time repeats the last one's, which the loader
// would drop (623,458 points on the first run, 623,448 after).
TEST(Phantom, StudyGeneratedAndCachedAreTheSame) {
    const auto dir = std::filesystem::path(PATHLET_TEST_BINARY_DIR) / "phantom-cache-study";
    std::filesystem::remove_all(dir);
    setenv("XDG_CACHE_HOME", dir.c_str(), 1);
    const Scene made = phantom::load_or_make_phantom("study");
    const Scene loaded = phantom::load_or_make_phantom("study");
    EXPECT_EQ(loaded.source, phantom::phantom_cache_path("study"));  // came from the cache
    unsetenv("XDG_CACHE_HOME");
    EXPECT_EQ(made.lines.point_count(), loaded.lines.point_count());
    EXPECT_EQ(made.lines.line_count(), loaded.lines.line_count());
    EXPECT_EQ(made.lines.time, loaded.lines.time);
    EXPECT_EQ(made.lines.position, loaded.lines.position);
}

// "small:density=3": three times the lines, the first third the phantom at density 1 point for
// point, the rest new lines (more seeds: not copies of the first third) in the same vessel and
// time span; the same bytes on one thread and on every core.
TEST(Phantom, DensityGivesNTimesTheLinesDeterministically) {
    auto o = phantom::phantom_preset("small:density=3");
    ASSERT_EQ(o.trace.density, 3);
    const Scene dense = phantom::make_phantom(o);
    const Pathlines& base = small_phantom().lines;
    const Pathlines& d = dense.lines;
    const size_t n = base.line_count();
    ASSERT_EQ(d.line_count(), 3 * n);
    EXPECT_EQ(d.time.size(), d.point_count());
    EXPECT_EQ(d.velocity.size(), d.point_count());
    EXPECT_EQ(dense.source, "phantom:small:density=3");
    // The first block is the phantom itself.
    ASSERT_GE(d.point_count(), base.point_count());
    EXPECT_TRUE(std::equal(base.position.begin(), base.position.end(), d.position.begin()));
    EXPECT_TRUE(std::equal(base.time.begin(), base.time.end(), d.time.begin()));
    // The other blocks: new lines (few copies of their accepted line), inside its bounds and span.
    const Bounds b = base.bounds();
    size_t copies = 0;
    for (size_t k = n; k < d.line_count(); ++k) {
        const LineRange r = d.lines[k], src = d.lines[k % n];
        ASSERT_GE(r.count, 2u);
        copies += r.count == src.count && std::equal(d.position.begin() + r.first, d.position.begin() + r.first + r.count,
                                                     d.position.begin() + src.first);
        for (uint32_t i = r.first; i < r.first + r.count; ++i) {
            ASSERT_GE(d.time[i], 0.0f);
            ASSERT_LE(d.time[i], 4.0f);
            ASSERT_TRUE(glm::all(glm::greaterThan(d.position[i], b.lo - 10.0f)) &&
                        glm::all(glm::lessThan(d.position[i], b.hi + 10.0f)));
        }
    }
    EXPECT_LT(copies, n / 10) << "companions are new lines, not copies";
    o.trace.threads = 1;
    const Scene again = phantom::make_phantom(o);
    EXPECT_EQ(again.lines.position, d.position);
    EXPECT_EQ(again.lines.time, d.time);
}

TEST(Phantom, DensityIsPartOfTheNameAndItsCache) {
    EXPECT_EQ(phantom::phantom_preset("study").trace.density, 1);
    EXPECT_EQ(phantom::phantom_preset("study:density=16").trace.density, 16);
    EXPECT_NE(phantom::phantom_cache_path("study:density=16"), phantom::phantom_cache_path("study"));
    EXPECT_NE(phantom::phantom_cache_path("study:density=16").find("density16"), std::string::npos);
    for (const char* bad : {"study:density=0", "study:density=65", "study:density=x", "study:density=4x",
                            "study:dense=4", "study:", "huge:density=2"}) {
        try {
            phantom::phantom_preset(bad);
            ADD_FAILURE() << bad << " was accepted";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(std::string(bad).substr(0, std::string(bad).find(':'))), std::string::npos)
                << e.what();
        }
    }
}
