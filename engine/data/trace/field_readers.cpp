#include "field_readers.hpp"

#include "io/file_bytes.hpp"

#include <algorithm>

namespace pathlet::trace {

VelocityField load_velocity_field(const std::string& path) {
    std::string ext = io::lower_extension(path);
    const std::string bytes = io::read_file_bytes(path);
    const std::string_view head = std::string_view(bytes).substr(0, 512);
    if (head.rfind("\x89HDF\r\n\x1a\n", 0) == 0 || ext == ".h5" || ext == ".hdf5") return read_flownet_h5(path);
    if (head.rfind("# vtk DataFile", 0) == 0) return read_vtk_legacy_field(bytes, path);
    if (head.find("<VTKFile") != std::string_view::npos) return read_vti_field(bytes, path);
    if (ext == ".vtk") return read_vtk_legacy_field(bytes, path);
    if (ext == ".vti") return read_vti_field(bytes, path);
    throw DataError(path + ": byte 0: not a velocity volume (expected VTK legacy STRUCTURED_POINTS, .vti or 4DFlowNet .h5)");
}

}  // namespace pathlet::trace
