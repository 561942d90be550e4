// The plugin ABI. A pass plugin is a MODULE library named pathlet_<name>.so exporting one
// extern "C" function, pathlet_plugin_v1, that returns a descriptor, and the symbol
// pathlet_sdk_<hash> (PATHLET_SDK_SYMBOL) naming the SDK headers it was built against. Before
// loading, the host reads the file's ELF symbol table: without the entry point, or with another
// SDK's symbol, the file is never opened. After loading it checks abi_version and the build
// fingerprint (C++ objects cross the boundary, so compiler, standard library and SDK headers
// must match) before it calls register_passes.
#pragma once

#include <pathlet/pass.hpp>
#include <pathlet/sdk_fingerprint.hpp>

#include <cstdint>

#define PATHLET_PLUGIN_ABI_VERSION 1
#define PATHLET_PLUGIN_ENTRY "pathlet_plugin_v1"

#ifndef PATHLET_BUILD_FINGERPRINT_STR
#define PATHLET_STR2(x) #x
#define PATHLET_STR(x) PATHLET_STR2(x)
// compiler + libstdc++ version + dual-ABI flag + C++ standard + SDK headers
#define PATHLET_BUILD_FINGERPRINT_STR                                                          \
    "gcc-" PATHLET_STR(__GNUC__) "." PATHLET_STR(__GNUC_MINOR__) "/glibcxx-" PATHLET_STR(     \
        __GLIBCXX__) "/cxx11abi-" PATHLET_STR(_GLIBCXX_USE_CXX11_ABI) "/std-" PATHLET_STR(__cplusplus) \
        "/sdk-" PATHLET_SDK_FINGERPRINT
#endif

// The SDK stamp the host reads from the ELF symbol table before it loads the file. Part of
// PATHLET_PLUGIN; a plugin that writes its entry point by hand adds it once.
#define PATHLET_SDK_STAMP                                                                    \
    extern "C" __attribute__((visibility("default"), used)) const char PATHLET_SDK_SYMBOL[] = \
        PATHLET_SDK_FINGERPRINT;

namespace pathlet {

// Handed to the plugin: it adds its pass types here.
class PassSink {
public:
    virtual ~PassSink() = default;
    virtual void add(PassTypeInfo info) = 0;
};

extern "C" {
struct PluginDescriptor {
    uint32_t abi_version;        // PATHLET_PLUGIN_ABI_VERSION
    uint32_t struct_size;        // sizeof(PluginDescriptor)
    const char* fingerprint;     // PATHLET_BUILD_FINGERPRINT_STR
    const char* name;            // human name of the plugin
    void (*register_passes)(PassSink* sink);
};
}

}  // namespace pathlet

// One per plugin .cpp (a plugin may register several types):
//   PATHLET_PLUGIN("my_fade", { sink->add(my_fade_type()); })
#define PATHLET_PLUGIN(plugin_name, ...)                                                     \
    PATHLET_SDK_STAMP                                                                        \
    static void pathlet_register_impl_(::pathlet::PassSink* sink) { __VA_ARGS__ }           \
    extern "C" __attribute__((visibility("default"))) const ::pathlet::PluginDescriptor*    \
    pathlet_plugin_v1() {                                                                    \
        static const ::pathlet::PluginDescriptor d{PATHLET_PLUGIN_ABI_VERSION,                \
                                                   sizeof(::pathlet::PluginDescriptor),       \
                                                   PATHLET_BUILD_FINGERPRINT_STR, plugin_name, \
                                                   &pathlet_register_impl_};                  \
        return &d;                                                                           \
    }
