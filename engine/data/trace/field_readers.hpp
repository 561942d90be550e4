// Velocity-volume readers. load_velocity_field picks one by content, then extension:
//   VTK legacy STRUCTURED_POINTS (.vtk; ASCII or big-endian BINARY; POINT_DATA VECTORS and
//     SCALARS),
//   VTK XML ImageData (.vti; ascii, inline base64, appended raw/base64, zlib),
//   HDF5 in the 4DFlowNet layout (.h5; see read_flownet_h5).
// Bad input throws DataError "<file>: <place>: <what>"; declared sizes are checked against
// the file size before anything is allocated.
#pragma once

#include "velocity_field.hpp"

#include <string>
#include <string_view>

namespace pathlet::trace {

VelocityField load_velocity_field(const std::string& path);

VelocityField read_vtk_legacy_field(std::string_view bytes, const std::string& path);
VelocityField read_vti_field(std::string_view bytes, const std::string& path);

// 4DFlowNet HDF5: datasets u, v, w (velocity, m/s) and optional mask, float32 of shape
// (t, i, j, k) with k varying fastest; dx = voxel size in mm (scalar or (1,3)).
// Mapping: k -> x, j -> y, i -> z (the file's fastest axis is our x, as in VTK), origin 0,
// spacing dx mm. u is the component along i, v along j, w along k, so velocity
// (x, y, z) = (w, v, u), converted to mm/s. Upstream does not document this; we chose it
// because it makes the CFD field divergence-free (rms central-difference divergence in the
// mask interior 2.7 vs 39 for u -> x on example_data_HR.h5). Frames are 1/t s apart unless a
// `dt` dataset is present.
VelocityField read_flownet_h5(const std::string& path);

}  // namespace pathlet::trace
