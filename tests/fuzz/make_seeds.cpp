// Writes a small seed corpus per fuzz target (a few KB each) with the project's own writers,
// so seeds follow the formats as they evolve: make_seeds OUT_DIR SOURCE_DIR.
#include "io/mesh_io.hpp"
#include "io/pathline_formats.hpp"
#include "io/pathline_io.hpp"
#include "io/native_cache.hpp"
#include "io/tract_formats.hpp"
#include <pathlet/scene.hpp>

#include <elf.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>

using namespace pathlet;
namespace fs = std::filesystem;

namespace {
// A minimal plugin as the host's ELF check reads it: header, .dynsym (the entry point and an SDK
// stamp) and .dynstr, with section headers; nothing loadable. libFuzzer mutates from here.
std::string tiny_plugin_elf() {
    const std::string strs = std::string("\0pathlet_plugin_v1\0pathlet_sdk_0123456789abcdef\0", 49);
    Elf64_Sym syms[3] = {};
    syms[1].st_name = 1;
    syms[1].st_info = ELF64_ST_INFO(STB_GLOBAL, STT_FUNC);
    syms[1].st_shndx = 1;
    syms[2].st_name = 19;
    syms[2].st_info = ELF64_ST_INFO(STB_GLOBAL, STT_OBJECT);
    syms[2].st_shndx = 1;
    const size_t str_at = sizeof(Elf64_Ehdr), sym_at = 128, sh_at = sym_at + sizeof syms;
    Elf64_Ehdr eh = {};
    std::memcpy(eh.e_ident, ELFMAG, SELFMAG);
    eh.e_ident[EI_CLASS] = ELFCLASS64;
    eh.e_ident[EI_DATA] = ELFDATA2LSB;
    eh.e_ident[EI_VERSION] = EV_CURRENT;
    eh.e_type = ET_DYN;
#if defined(__aarch64__)
    eh.e_machine = EM_AARCH64;
#else
    eh.e_machine = EM_X86_64;
#endif
    eh.e_version = EV_CURRENT;
    eh.e_ehsize = sizeof eh;
    eh.e_shoff = sh_at;
    eh.e_shentsize = sizeof(Elf64_Shdr);
    eh.e_shnum = 3;
    Elf64_Shdr sh[3] = {};
    sh[1].sh_type = SHT_DYNSYM;
    sh[1].sh_offset = sym_at;
    sh[1].sh_size = sizeof syms;
    sh[1].sh_entsize = sizeof(Elf64_Sym);
    sh[1].sh_link = 2;
    sh[2].sh_type = SHT_STRTAB;
    sh[2].sh_offset = str_at;
    sh[2].sh_size = strs.size();
    std::string out(sh_at + sizeof sh, '\0');
    std::memcpy(out.data(), &eh, sizeof eh);
    std::memcpy(out.data() + str_at, strs.data(), strs.size());
    std::memcpy(out.data() + sym_at, syms, sizeof syms);
    std::memcpy(out.data() + sh_at, sh, sizeof sh);
    return out;
}

void put(const fs::path& dir, const std::string& name, const std::string& bytes) {
    fs::create_directories(dir);
    std::ofstream(dir / name, std::ios::binary) << bytes;
}
std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}
}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) {
        std::cerr << "usage: make_seeds OUT_DIR SOURCE_DIR\n";
        return 2;
    }
    const fs::path out = argv[1], src = argv[2];
    Pathlines p;  // two short pathlines with time and velocity
    for (int l = 0; l < 2; ++l) {
        p.lines.push_back({uint32_t(p.position.size()), 4});
        for (int k = 0; k < 4; ++k) {
            p.position.push_back({float(k), float(l), 0.5f * float(k * l)});
            p.time.push_back(0.5f * float(k));
            p.velocity.push_back({2.0f, 0.0f, float(l)});
        }
    }
    using E = io::VtpWriteOptions::Encoding;
    put(out / "vtk_legacy", "ascii.vtk", io::write_vtk_legacy(p, {false, false}));
    put(out / "vtk_legacy", "binary.vtk", io::write_vtk_legacy(p, {true, false}));
    put(out / "vtk_legacy", "v51.vtk", io::write_vtk_legacy(p, {false, true}));
    for (E e : {E::Ascii, E::Inline, E::AppendedRaw, E::AppendedBase64})
        for (bool z : {false, true}) {
            io::VtpWriteOptions o;
            o.encoding = e;
            o.zlib = z && e != E::Ascii;
            put(out / "vtp", "v" + std::to_string(int(e)) + std::to_string(z) + ".vtp", io::write_vtp(p, o));
        }
    put(out / "text_rows", "rows.txt", "0 0 0 1 0 0 2 0 1\n0 1 0 1 1 0 2 1 1 3 1 2\n");
    put(out / "native", "lines.pathlet", io::encode_native(p));
    Pathlines pu = p;  // the units block and field data
    pu.units = {"mm", "s", "mm/s"};
    put(out / "native", "units.pathlet", io::encode_native(pu));
    put(out / "vtk_legacy", "units_binary.vtk", io::write_vtk_legacy(pu, {true, false}));
    put(out / "vtp", "units.vtp", io::write_vtp(pu, {}));
    {
        io::TrkWriteOptions o;
        o.dims = {8, 8, 8};
        put(out / "trk", "v2.trk", io::write_trk(p, o));
        o.version = 1;
        put(out / "trk", "v1.trk", io::write_trk(p, o));
        o.version = 2;
        o.big_endian = true;
        o.scalars = 2;
        o.properties = 1;
        o.voxel_order = "LPS";
        o.vox_to_ras = glm::mat4(glm::vec4(-2, 0, 0, 0), glm::vec4(0, -2, 0, 0), glm::vec4(0, 0, 2, 0), glm::vec4(16, 16, 0, 1));
        o.voxel_size = glm::vec3(2.0f);
        put(out / "trk", "big_scalars.trk", io::write_trk(p, o));
        put(out / "tck", "f32le.tck", io::write_tck(p));
        put(out / "tck", "f64be.tck", io::write_tck(p, {.big_endian = true, .float64 = true}));
    }
    Mesh m;
    m.position = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    m.index = {0, 1, 2, 0, 1, 3, 0, 2, 3, 1, 2, 3};
    const fs::path tmp = fs::temp_directory_path() / "pathlet_make_seeds";
    fs::create_directories(tmp);
    for (const char* ext : {".glb", ".gltf", ".stl", ".obj"}) {
        io::save_mesh(m, (tmp / ("m" + std::string(ext))).string());
        std::string kind = std::string(ext).substr(1);
        put(out / kind, std::string("mesh") + ext, slurp(tmp / ("m" + std::string(ext))));
    }
    put(out / "stl", "ascii.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                                  "endloop\nendfacet\nendsolid t\n");
    fs::remove_all(tmp);
    put(out / "vtk_field", "field.vtk",
        "# vtk DataFile Version 3.0\nf\nASCII\nDATASET STRUCTURED_POINTS\nDIMENSIONS 2 2 2\nSPACING 1 1 1\n"
        "ORIGIN 0 0 0\nPOINT_DATA 8\nVECTORS velocity float\n1 0 0 1 0 0 1 0 0 1 0 0 0 1 0 0 1 0 0 1 0 0 1 0\n"
        "SCALARS mask float 1\nLOOKUP_TABLE default\n1 1 1 1 1 1 1 0\n");
    put(out / "vti", "field.vti",
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
        "<ImageData WholeExtent=\"0 1 0 1 0 1\" Origin=\"0 0 0\" Spacing=\"1 1 1\">\n<Piece Extent=\"0 1 0 1 0 1\">\n"
        "<PointData Vectors=\"velocity\">\n<DataArray type=\"Float32\" Name=\"velocity\" NumberOfComponents=\"3\" "
        "format=\"ascii\">\n1 0 0 1 0 0 1 0 0 1 0 0 0 1 0 0 1 0 0 1 0 0 1 0\n</DataArray>\n</PointData>\n</Piece>\n"
        "</ImageData>\n</VTKFile>\n");
    put(out / "hdf5", "not_hdf5.h5", "\x89HDF\r\n\x1a\n");  // the signature alone; libFuzzer grows it
    for (const auto& e : fs::directory_iterator(src / "graphs"))
        if (e.path().extension() == ".json") put(out / "graph", e.path().filename().string(), slurp(e.path()));
    put(out / "camera", "path.json",
        R"({"keyframes": [{"time": 0, "eye": [0, 0, 5], "target": [0, 0, 0], "up": [0, 1, 0], "fov": 40},)"
        R"( {"time": 2, "eye": [5, 0, 0], "target": [0, 0, 0], "up": [0, 1, 0], "fov": 30}]})");
    for (const auto& e : fs::directory_iterator(src / "graphs" / "experiments"))
        if (e.path().extension() == ".json") put(out / "experiment", e.path().filename().string(), slurp(e.path()));
    put(out / "view_script", "events.json",
        R"([{"frame": 0, "key": "space"}, {"frame": 1, "drag": [40, 0], "button": "left"}, {"frame": 2, "scroll": 2},)"
        R"( {"frame": 3, "set": "window=2"}, {"frame": 4, "graph": "isl"}, {"frame": 5, "reload": true}])");
    put(out / "elf", "tiny_plugin.so", tiny_plugin_elf());
    std::cout << "seeds written to " << out.string() << "\n";
    return 0;
}
