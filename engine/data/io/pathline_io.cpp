// Pathline load/save dispatch: content sniffing picks the reader; every reader ends in the
// shared repair step; every writer's bytes go through write_file_atomic.
#include "pathline_io.hpp"

#include "byte_reader.hpp"
#include "file_bytes.hpp"
#include "native_cache.hpp"
#include "pathline_formats.hpp"
#include "tract_formats.hpp"
#include "units.hpp"
#include "util/atomic_file.hpp"

namespace pathlet::io {

namespace {
Pathlines read_any(const std::string& path, const LoadOptions& opts, LoadReport& r) {
    std::string bytes = read_file_bytes(path);
    switch (Sniffed s = sniff(bytes, path)) {
        case Sniffed::VtkLegacy: return assemble_pathlines(read_vtk_legacy(bytes, path, r), opts, r, path);
        case Sniffed::VtkXml: return assemble_pathlines(read_vtp(bytes, path, r), opts, r, path);
        case Sniffed::Native: return decode_native(bytes, path, r);
        case Sniffed::TextRows: return read_text_rows(bytes, path, opts, r);
        case Sniffed::TrackVis: return read_trk(bytes, path, r);
        case Sniffed::MrtrixTck: return read_tck(bytes, path, r);
        case Sniffed::Unknown:
            fail_at(path, at_byte(0), "unrecognised pathline format (expected VTK legacy .vtk, VTK XML .vtp, .pathlet cache, "
                                      "TrackVis .trk, MRtrix .tck, or plain-text rows of x y z ...)");
        default:
            fail_at(path, at_byte(0), std::string("this is a ") + sniffed_name(s) +
                                          " mesh, not pathlines; load it as a mesh (load_mesh / --mesh)");
    }
}
}  // namespace

Pathlines load_pathlines(const std::string& path, const LoadOptions& opts, LoadReport* report) {
    LoadReport local;
    LoadReport& r = report ? *report : local;
    Pathlines pl = read_any(path, opts, r);
    if (opts.pseudo_time && pl.timeless) {
        pl.timeless = false;
        r.warnings.push_back("--pseudo-time: the streamlines animate along their pseudo-time");
    }
    try {
        apply_units_option(pl.units, opts.units);
    } catch (const std::invalid_argument& e) {
        throw DataError(path + ": " + e.what());
    }
    return pl;
}

PathlineFormat format_from_extension(const std::string& path) {
    std::string ext = lower_extension(path);
    if (ext == ".vtk") return PathlineFormat::VtkBinary;
    if (ext == ".vtp") return PathlineFormat::VtpZlib;
    if (ext == ".pathlet") return PathlineFormat::Native;
    fail_at(path, at_byte(0), "cannot choose a pathline format from extension '" + ext + "' (use .vtk, .vtp or .pathlet)");
}

void save_pathlines(const Pathlines& lines, const std::string& path, PathlineFormat fmt) {
    lines.check_consistent(path);
    using E = VtpWriteOptions::Encoding;
    auto vtp = [&](E e, bool zlib) {
        VtpWriteOptions o;
        o.encoding = e;
        o.zlib = zlib;
        return write_vtp(lines, o);
    };
    std::string bytes;
    switch (fmt) {
        case PathlineFormat::VtkAscii: bytes = write_vtk_legacy(lines, {false, false}); break;
        case PathlineFormat::VtkBinary: bytes = write_vtk_legacy(lines, {true, false}); break;
        case PathlineFormat::VtpAscii: bytes = vtp(E::Ascii, false); break;
        case PathlineFormat::VtpBinary: bytes = vtp(E::Inline, false); break;
        case PathlineFormat::VtpAppendedRaw: bytes = vtp(E::AppendedRaw, false); break;
        case PathlineFormat::VtpAppendedBase64: bytes = vtp(E::AppendedBase64, false); break;
        case PathlineFormat::VtpZlib: bytes = vtp(E::Inline, true); break;
        case PathlineFormat::Native: bytes = encode_native(lines); break;
    }
    try {
        write_file_atomic(path, bytes);
    } catch (const std::runtime_error& e) {
        throw DataError(e.what());
    }
}

}  // namespace pathlet::io
