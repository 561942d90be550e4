#include "phantom.hpp"

#include "trace/marching_cubes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <thread>

namespace pathlet::phantom {
namespace {

struct Aneurysm {
    glm::vec3 centre{0.0f}, axis{0.0f};  // vortex axis
    float radius = 0.0f;
};

Aneurysm place_aneurysm(const PhantomOptions& o, const std::vector<CenterlineSample>& cl) {
    // 40 mm down the descending aorta, bulging to the left (+x) of the vessel.
    const float s_target = arch_end_s(o.shape) + 40.0f;
    const auto it = std::lower_bound(cl.begin(), cl.end(), s_target, [](const auto& c, float s) { return c.s < s; });
    const CenterlineSample& c = it == cl.end() ? cl.back() : *it;
    glm::vec3 out = glm::vec3(1, 0, 0) - glm::dot(glm::vec3(1, 0, 0), c.tangent) * c.tangent;
    out = glm::normalize(out);
    Aneurysm a;
    a.radius = o.aneurysm_radius;
    a.centre = c.position + out * (c.radius + 0.45f * a.radius);
    a.axis = glm::normalize(glm::cross(c.tangent, out));  // flow at the neck runs along the tangent
    return a;
}

// Nearest centreline sample per voxel, found by stamping each sample's neighbourhood.
// Threads own z-slabs and visit samples in order, so ties resolve the same way every run.
std::vector<uint32_t> nearest_samples(const trace::Grid& g, const std::vector<CenterlineSample>& cl, float reach) {
    std::vector<uint32_t> best(g.count(), UINT32_MAX);
    std::vector<float> d2(g.count(), std::numeric_limits<float>::max());
    const int nthreads = int(std::max(1u, std::thread::hardware_concurrency()));
    auto slab = [&](int k0, int k1) {
        for (uint32_t s = 0; s < cl.size(); ++s) {
            const glm::vec3 r(cl[s].radius + reach);
            const glm::ivec3 lo = glm::max(glm::ivec3(glm::floor(g.to_grid(cl[s].position - r))), glm::ivec3(0, 0, k0));
            const glm::ivec3 hi = glm::min(glm::ivec3(glm::ceil(g.to_grid(cl[s].position + r))), glm::ivec3(g.dims.x - 1, g.dims.y - 1, k1 - 1));
            for (int k = lo.z; k <= hi.z; ++k)
                for (int j = lo.y; j <= hi.y; ++j)
                    for (int i = lo.x; i <= hi.x; ++i) {
                        const size_t idx = g.index(i, j, k);
                        const glm::vec3 d = g.point({i, j, k}) - cl[s].position;
                        const float dd = glm::dot(d, d);
                        if (dd < d2[idx]) d2[idx] = dd, best[idx] = s;
                    }
        }
    };
    std::vector<std::thread> pool;
    const int per = (g.dims.z + nthreads - 1) / nthreads;
    for (int t = 0; t < nthreads; ++t) {
        const int k0 = t * per, k1 = std::min(g.dims.z, k0 + per);
        if (k0 < k1) pool.emplace_back(slab, k0, k1);
    }
    for (auto& th : pool) th.join();
    return best;
}

}  // namespace

PhantomOptions phantom_preset(const std::string& spec) {
    const size_t colon = spec.find(':');
    const std::string preset = spec.substr(0, colon);
    PhantomOptions o;
    o.preset = preset;
    if (colon != std::string::npos) {
        const std::string opt = spec.substr(colon + 1), key = "density=";
        size_t used = 0;
        int n = 0;
        try {
            if (opt.rfind(key, 0) == 0) n = std::stoi(opt.substr(key.size()), &used);
        } catch (const std::exception&) {
            n = 0;
        }
        if (opt.rfind(key, 0) != 0 || used + key.size() != opt.size() || n < 1 || n > kMaxDensity)
            throw std::invalid_argument("phantom '" + spec + "': expected " + preset + ":density=N with N in 1.." +
                                        std::to_string(kMaxDensity));
        o.trace.density = n;
    }
    auto& t = o.trace;
    t.time_begin = 0.0f;
    t.pulsatile = trace::Pulsatile{1.0f, 2.85f};  // 60 bpm; cycle-mean factor ~1
    t.max_dt = 0.01f;
    t.seed = 20240611;
    t.smooth_passes = 3;
    if (preset == "study") {
        // Tuned to the study data set: ~3169 lines, ~644k points, 18 s.
        o.voxel = 0.85f;
        t.time_end = 18.0f;
        t.step = 0.5f;
        t.max_line_time = 1.6f;
        t.min_length = 20.0f;
        t.min_distance = 0.5f;
        t.close_fraction = 0.9f;
        t.resample_step = 0.62f;
    } else if (preset == "small") {
        // ~300 lines on a 2 mm grid: fast enough for unit tests.
        o.voxel = 2.0f;
        t.time_end = 4.0f;
        t.step = 0.5f;
        t.max_line_time = 1.0f;
        t.min_length = 20.0f;
        t.min_distance = 2.0f;
        t.close_fraction = 0.8f;
        t.resample_step = 2.0f;
    } else {
        throw std::invalid_argument("unknown phantom preset '" + preset + "' (expected study or small, optionally with :density=N)");
    }
    return o;
}

trace::VelocityField make_phantom_field(const PhantomOptions& o) {
    const auto cl = make_centerline(o.shape);
    const Aneurysm an = o.aneurysm ? place_aneurysm(o, cl) : Aneurysm{};

    // Grid around everything with three voxels of margin, so the wall closes.
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const auto& c : cl) lo = glm::min(lo, c.position - c.radius), hi = glm::max(hi, c.position + c.radius);
    if (o.aneurysm) lo = glm::min(lo, an.centre - an.radius), hi = glm::max(hi, an.centre + an.radius);
    lo -= 3.0f * o.voxel;
    hi += 3.0f * o.voxel;
    trace::VelocityField f;
    f.source = "phantom:" + o.preset;
    f.units = {"mm", "", "mm/s"};
    f.grid.origin = glm::floor(lo / o.voxel) * o.voxel;
    f.grid.spacing = glm::vec3(o.voxel);
    f.grid.dims = glm::ivec3(glm::ceil((hi - f.grid.origin) / o.voxel)) + 1;
    f.frames.assign(1, std::vector<glm::vec3>(f.grid.count(), glm::vec3(0.0f)));
    f.frame_times = {0.0f};
    f.mask.assign(f.grid.count(), 0.0f);

    const std::vector<uint32_t> near = nearest_samples(f.grid, cl, 2.0f * o.voxel);
    const float r_root = cl.front().radius;
    for (size_t idx = 0; idx < f.grid.count(); ++idx) {
        const glm::vec3 p = f.grid.point(f.grid.coord(idx));
        float sd = std::numeric_limits<float>::max();  // signed distance to the wall, negative inside
        float um = 0.0f;
        glm::vec3 v(0.0f);
        if (near[idx] != UINT32_MAX) {
            const CenterlineSample& c = cl[near[idx]];
            const glm::vec3 d = p - c.position;
            const float axial = glm::dot(d, c.tangent);
            const glm::vec3 radial = d - axial * c.tangent;
            const float r = glm::length(radial), rho = r / c.radius;
            sd = r - c.radius;  // the tube, with flat caps at both ends
            if (near[idx] == 0) sd = std::max(sd, -axial);
            if (near[idx] + 1 == cl.size()) sd = std::max(sd, axial);
            // Mean speed scales with the area so the flow rate is conserved along the taper.
            um = o.mean_speed * (r_root * r_root) / (c.radius * c.radius);
            if (rho < 1.0f) {
                v = 2.0f * um * (1.0f - rho * rho) * c.tangent;  // Poiseuille profile
                if (r > 1e-6f) v += c.swirl * um * 4.0f * rho * (1.0f - rho) * glm::cross(c.tangent, radial / r);
            }
        }
        if (o.aneurysm) {
            const glm::vec3 q = p - an.centre;
            const float dist = glm::length(q), sd_sac = dist - an.radius;
            if (sd_sac < sd && dist > 1e-6f) {
                // Vortex in the sac, driven by the passing flow; blended in across the tube wall.
                const float w = smoothstep(-1.0f, 1.0f, sd);
                const float e = dist / an.radius;
                const float drive = 0.8f * o.mean_speed * 4.0f * e * std::max(0.0f, 1.0f - e);
                v = (1.0f - w) * v + w * drive * glm::cross(an.axis, q / dist);
            }
            sd = std::min(sd, sd_sac);
        }
        if (sd > 2.0f * o.voxel) continue;
        f.mask[idx] = std::clamp(0.5f - sd / o.voxel, 0.0f, 1.0f);
        f.frames[0][idx] = v;
    }
    return f;
}

Scene make_phantom(const PhantomOptions& o, const trace::Progress& progress, trace::TraceStats* stats) {
    trace::report(progress, 0.0, "phantom field");
    const trace::VelocityField field = make_phantom_field(o);
    // The wall first (quick), then the tracer reports its own progress.
    Scene scene;
    scene.mesh = trace::marching_cubes(field.grid, field.mask, 0.5f);
    scene.lines = trace::trace_pathlines(field, o.trace, progress, stats);
    scene.source = "phantom:" + o.preset + (o.trace.density > 1 ? ":density=" + std::to_string(o.trace.density) : "");
    return scene;
}

}  // namespace pathlet::phantom
