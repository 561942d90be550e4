// A plugin file's ELF dynamic symbol table, read without loading it (no dlopen, so none of its
// code runs): does it define the entry point pathlet_plugin_v1, and which SDK was it built
// against (its pathlet_sdk_<hash> symbol)? The host checks both before it opens a file.
#pragma once

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace pathlet {

// The file is not a 64-bit little-endian ELF shared object of this machine with a readable
// dynamic symbol table; the message says which part is wrong.
struct ElfError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct PluginSymbols {
    bool entry = false;  // defines the function pathlet_plugin_v1
    std::string sdk;     // <hash> of a defined pathlet_sdk_<hash>; "" when there is none
};

// `read(offset, size)` returns exactly `size` bytes of the file at `offset`, or throws ElfError.
using ElfReader = std::function<std::string(uint64_t offset, uint64_t size)>;
PluginSymbols read_plugin_symbols(const ElfReader& read);
PluginSymbols read_plugin_symbols(std::string_view bytes);  // the whole file in memory (fuzzing, tests)
PluginSymbols read_plugin_symbols_of_file(const std::string& path);

}  // namespace pathlet
