#include "plugin_elf.hpp"

#include <elf.h>
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace pathlet {

namespace {

#if defined(__x86_64__)
constexpr uint16_t kMachine = EM_X86_64;
#elif defined(__aarch64__)
constexpr uint16_t kMachine = EM_AARCH64;
#else
#error "plugin_elf: add this machine's EM_ constant"
#endif

// The dynamic symbol table of a plugin has a few hundred entries; these caps only keep a
// corrupt header from asking for gigabytes.
constexpr uint64_t kMaxTable = 64ull << 20;

template <class T>
T load(const std::string& bytes, size_t at = 0) {
    T v;
    std::memcpy(&v, bytes.data() + at, sizeof v);
    return v;
}

}  // namespace

PluginSymbols read_plugin_symbols(const ElfReader& read) {
    std::string head;
    try {
        head = read(0, sizeof(Elf64_Ehdr));
    } catch (const ElfError&) {
        head.clear();  // shorter than an ELF header
    }
    if (head.size() < sizeof(Elf64_Ehdr) || std::memcmp(head.data(), ELFMAG, SELFMAG) != 0)
        throw ElfError("not an ELF file");
    if (head[EI_CLASS] != ELFCLASS64 || head[EI_DATA] != ELFDATA2LSB)
        throw ElfError("not a 64-bit little-endian ELF file");
    const auto eh = load<Elf64_Ehdr>(head);
    if (eh.e_type != ET_DYN) throw ElfError("not a shared library (ELF type " + std::to_string(eh.e_type) + ")");
    if (eh.e_machine != kMachine) throw ElfError("built for another machine (ELF machine " + std::to_string(eh.e_machine) + ")");
    if (eh.e_shoff == 0 || eh.e_shnum == 0) throw ElfError("no section headers (stripped with sstrip?)");
    if (eh.e_shentsize != sizeof(Elf64_Shdr)) throw ElfError("unexpected section header size");
    const std::string shdrs = read(eh.e_shoff, uint64_t(eh.e_shnum) * sizeof(Elf64_Shdr));
    for (size_t i = 0; i < eh.e_shnum; ++i) {
        const auto sym_sec = load<Elf64_Shdr>(shdrs, i * sizeof(Elf64_Shdr));
        if (sym_sec.sh_type != SHT_DYNSYM) continue;
        if (sym_sec.sh_entsize != sizeof(Elf64_Sym) || sym_sec.sh_size > kMaxTable || sym_sec.sh_size % sizeof(Elf64_Sym))
            throw ElfError("malformed dynamic symbol table");
        if (sym_sec.sh_link == 0 || sym_sec.sh_link >= eh.e_shnum) throw ElfError("dynamic symbol table without strings");
        const auto str_sec = load<Elf64_Shdr>(shdrs, size_t(sym_sec.sh_link) * sizeof(Elf64_Shdr));
        if (str_sec.sh_type != SHT_STRTAB || str_sec.sh_size > kMaxTable) throw ElfError("malformed dynamic string table");
        const std::string syms = read(sym_sec.sh_offset, sym_sec.sh_size);
        const std::string strs = read(str_sec.sh_offset, str_sec.sh_size);
        PluginSymbols out;
        for (size_t k = 0; k < syms.size() / sizeof(Elf64_Sym); ++k) {
            const auto s = load<Elf64_Sym>(syms, k * sizeof(Elf64_Sym));
            if (s.st_shndx == SHN_UNDEF || s.st_name >= strs.size()) continue;  // imported, or a bad name
            const int bind = ELF64_ST_BIND(s.st_info), type = ELF64_ST_TYPE(s.st_info);
            if (bind != STB_GLOBAL && bind != STB_WEAK) continue;
            const char* name = strs.data() + s.st_name;
            const size_t len = strnlen(name, strs.size() - s.st_name);
            const std::string_view n(name, len);
            if (n == "pathlet_plugin_v1" && type == STT_FUNC) out.entry = true;
            if (n.rfind("pathlet_sdk_", 0) == 0 && type == STT_OBJECT) out.sdk = std::string(n.substr(12));
        }
        return out;
    }
    throw ElfError("no dynamic symbol table");
}

PluginSymbols read_plugin_symbols(std::string_view bytes) {
    return read_plugin_symbols([bytes](uint64_t offset, uint64_t size) {
        if (offset > bytes.size() || size > bytes.size() - offset)
            throw ElfError("truncated: a table lies beyond the end of the file");
        return std::string(bytes.substr(size_t(offset), size_t(size)));
    });
}

PluginSymbols read_plugin_symbols_of_file(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw ElfError(std::string("cannot read: ") + std::strerror(errno));
    struct Close {
        int fd;
        ~Close() { ::close(fd); }
    } close_fd{fd};
    const off_t end = ::lseek(fd, 0, SEEK_END);
    return read_plugin_symbols([fd, end](uint64_t offset, uint64_t size) {
        if (end < 0 || offset > uint64_t(end) || size > uint64_t(end) - offset)
            throw ElfError("truncated: a table lies beyond the end of the file");
        std::string out(size_t(size), '\0');
        size_t got = 0;
        while (got < size) {
            const ssize_t n = ::pread(fd, out.data() + got, size - got, off_t(offset + got));
            if (n <= 0) throw ElfError("cannot read at offset " + std::to_string(offset + got));
            got += size_t(n);
        }
        return out;
    });
}

}  // namespace pathlet
