// One libFuzzer target per importer, per JSON file kind and for the plugin ELF check, chosen at compile time
// (FUZZ_<KIND>; tests/fuzz/CMakeLists.txt builds one executable each). Every reader must
// either load or throw its documented error type naming the file; anything else (a crash,
// a sanitizer report, another exception, a giant allocation) is a finding.
#include "bench/experiment.hpp"
#include "graph/graph_model.hpp"
#include "plugin_elf.hpp"
#include "util/text.hpp"
#include "view/view_script.hpp"
#include "io/mesh_formats.hpp"
#include "io/native_cache.hpp"
#include "io/pathline_formats.hpp"
#include "io/raw_polylines.hpp"
#include "io/tract_formats.hpp"
#include "trace/field_readers.hpp"
#include "camera.hpp"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <unistd.h>

using namespace pathlet;

namespace {

void run(std::string_view bytes) {
    io::LoadReport r;
    const std::string f = "fuzz-input";
#if defined(FUZZ_VTK_LEGACY)
    io::assemble_pathlines(io::read_vtk_legacy(bytes, f, r), {}, r, f);
#elif defined(FUZZ_VTP)
    io::assemble_pathlines(io::read_vtp(bytes, f, r), {}, r, f);
#elif defined(FUZZ_TEXT_ROWS)
    io::read_text_rows(bytes, f, {}, r);
#elif defined(FUZZ_NATIVE)
    io::decode_native(bytes, f, r);
#elif defined(FUZZ_TRK)
    io::read_trk(bytes, f, r);
#elif defined(FUZZ_TCK)
    io::read_tck(bytes, f, r);
#elif defined(FUZZ_GLTF)
    io::read_gltf(bytes, false, f, r);
#elif defined(FUZZ_GLB)
    io::read_gltf(bytes, true, f, r);
#elif defined(FUZZ_STL)
    io::read_stl(bytes, !bytes.empty() && bytes.substr(0, 5) != "solid", f, r);
#elif defined(FUZZ_OBJ)
    io::read_obj(bytes, f, r);
#elif defined(FUZZ_VTK_FIELD)
    trace::read_vtk_legacy_field(bytes, f);
#elif defined(FUZZ_VTI)
    trace::read_vti_field(bytes, f);
#elif defined(FUZZ_HDF5)
    // HDF5 reads files: a per-process scratch file (libFuzzer runs one input at a time).
    static const std::string path = "/tmp/pathlet_fuzz_" + std::to_string(::getpid()) + ".h5";
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
    trace::read_flownet_h5(path);
#elif defined(FUZZ_GRAPH)
    GraphFile g = parse_graph_json(std::string(bytes), f);
    (void)g;
#elif defined(FUZZ_CAMERA)
    CameraPath::parse(std::string(bytes), f);
#elif defined(FUZZ_EXPERIMENT)
    cli::bench::parse_experiment(text::parse_json_of(f, std::string(bytes), "experiment file"), f);
#elif defined(FUZZ_VIEW_SCRIPT)
    view::parse_script(std::string(bytes), f);
#elif defined(FUZZ_ELF)
    // The check before a plugin is opened: its ELF symbol table, read from bytes.
    try {
        read_plugin_symbols(bytes);
    } catch (const ElfError&) {
    }
#else
#error "define one FUZZ_<KIND>"
#endif
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    try {
        run(std::string_view(reinterpret_cast<const char*>(data), size));
    } catch (const DataError&) {
    } catch (const GraphError&) {
    }
    return 0;  // any other exception escapes: libFuzzer reports it as a crash
}
