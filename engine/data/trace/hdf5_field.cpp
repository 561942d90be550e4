// 4DFlowNet HDF5 layout reader (see field_readers.hpp for the axis mapping).
#include "field_readers.hpp"
#include "util/input_limits.hpp"

#include <hdf5.h>

#include <array>
#include <memory>

namespace pathlet::trace {
namespace {

// Closes an HDF5 handle when it goes out of scope.
struct H5Handle {
    hid_t id = -1;
    herr_t (*close)(hid_t) = nullptr;
    ~H5Handle() {
        if (id >= 0 && close) close(id);
    }
};

constexpr size_t kMaxElements = size_t(1) << 30;  // 4 GiB of float32: refuse anything larger

struct Dataset {
    std::vector<hsize_t> shape;
    std::vector<float> data;
};

bool has_dataset(hid_t file, const char* name) { return H5Lexists(file, name, H5P_DEFAULT) > 0; }

Dataset read_dataset(hid_t file, const char* name, const std::string& path) {
    const std::string where = path + ": dataset '" + name + "': ";
    H5Handle ds{H5Dopen2(file, name, H5P_DEFAULT), H5Dclose};
    if (ds.id < 0) throw DataError(where + "cannot open");
    H5Handle space{H5Dget_space(ds.id), H5Sclose};
    const int rank = H5Sget_simple_extent_ndims(space.id);
    if (rank < 0 || rank > 8) throw DataError(where + "bad rank");
    Dataset out;
    out.shape.resize(size_t(rank));
    H5Sget_simple_extent_dims(space.id, out.shape.data(), nullptr);
    size_t n = 1;
    for (hsize_t d : out.shape) {
        if (d == 0 || n > kMaxElements / d) throw DataError(where + "declared size is too large or empty");
        n *= size_t(d);
    }
    // Compressed data may legitimately be much smaller than its size, but not absurdly so.
    // The declared size must be plausible from the bytes stored: uncompressed data holds
    // 1-8 bytes per element, deflate inflates at most ~1032:1 (io::max_inflate_ratio()).
    const hsize_t stored = H5Dget_storage_size(ds.id);
    if (stored == 0 && n > 1) throw DataError(where + "has no stored data");
    if (double(n) > double(stored) * io::max_inflate_ratio() + 64.0)
        throw DataError(where + "declares " + std::to_string(n) + " elements but stores only " + std::to_string(stored) +
                        " bytes (corrupt header, or beyond PATHLET_MAX_INFLATE_RATIO = " +
                        std::to_string(int(io::max_inflate_ratio())) + ")");
    out.data.resize(n);
    if (H5Dread(ds.id, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data.data()) < 0)
        throw DataError(where + "cannot read (truncated or not numeric)");
    return out;
}

}  // namespace

VelocityField read_flownet_h5(const std::string& path) {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // errors become DataError, not stderr noise
    if (H5Fis_hdf5(path.c_str()) <= 0) throw DataError(path + ": byte 0: not an HDF5 file (or truncated)");
    H5Handle file{H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
    if (file.id < 0) throw DataError(path + ": byte 0: cannot open HDF5 file (truncated?)");
    for (const char* name : {"u", "v", "w"})
        if (!has_dataset(file.id, name)) throw DataError(path + ": dataset '" + name + "': missing (need u, v, w)");

    const Dataset u = read_dataset(file.id, "u", path);
    const Dataset v = read_dataset(file.id, "v", path);
    const Dataset w = read_dataset(file.id, "w", path);
    if (u.shape.size() != 4 && u.shape.size() != 3)
        throw DataError(path + ": dataset 'u': expected shape (t, i, j, k) or (i, j, k)");
    if (v.shape != u.shape || w.shape != u.shape) throw DataError(path + ": datasets u, v, w differ in shape");
    const size_t off = u.shape.size() - 3;
    const size_t frames = off ? size_t(u.shape[0]) : 1;
    const size_t ni = u.shape[off], nj = u.shape[off + 1], nk = u.shape[off + 2];

    VelocityField f;
    f.source = path;
    f.grid.dims = {int(nk), int(nj), int(ni)};  // k -> x, j -> y, i -> z
    float dx = 1.0f;
    if (has_dataset(file.id, "dx")) {
        const Dataset d = read_dataset(file.id, "dx", path);
        dx = d.data.at(0);
        if (!(dx > 0.0f)) throw DataError(path + ": dataset 'dx': voxel size must be positive");
    }
    f.grid.spacing = glm::vec3(dx);
    f.units = {"mm", "", "mm/s"};  // 4DFlowNet: dx in mm, velocity in m/s (converted below)
    float dt = 1.0f / float(frames);
    if (has_dataset(file.id, "dt")) dt = read_dataset(file.id, "dt", path).data.at(0);
    const size_t per = ni * nj * nk;
    f.frames.resize(frames);
    for (size_t t = 0; t < frames; ++t) {
        f.frames[t].resize(per);
        // (i, j, k) with k fastest is already x-fastest order for dims (k, j, i).
        for (size_t q = 0; q < per; ++q) {
            const size_t s = t * per + q;
            // u runs along i, w along k: (x, y, z) = (w, v, u); m/s -> mm/s.
            f.frames[t][q] = 1000.0f * glm::vec3(w.data[s], v.data[s], u.data[s]);
        }
        f.frame_times.push_back(float(t) * dt);
    }
    if (has_dataset(file.id, "mask")) {
        const Dataset m = read_dataset(file.id, "mask", path);
        if (m.data.size() != per && m.data.size() != per * frames)
            throw DataError(path + ": dataset 'mask': shape does not match u");
        f.mask.assign(m.data.begin(), m.data.begin() + std::ptrdiff_t(per));  // first frame's mask
    }
    f.check();
    return f;
}

}  // namespace pathlet::trace
