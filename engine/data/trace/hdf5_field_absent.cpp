// The 4DFlowNet reader's stand-in in a build without HDF5 (PATHLET_WITH_HDF5=OFF, the lean
// bundle: Debian's HDF5 pulls curl, TLS and Kerberos, half of the bundle). Says so, naming the file.
#include "field_readers.hpp"

namespace pathlet::trace {

VelocityField read_flownet_h5(const std::string& path) {
    throw DataError(path + ": byte 0: this build has no HDF5 (built with PATHLET_WITH_HDF5=OFF, as the lean bundle "
                           "is): trace 4DFlowNet .h5 volumes with the full build, or give a .vti or VTK volume");
}

}  // namespace pathlet::trace
