# Writes the SDK fingerprint header: a hash of the SDK headers' text, so a plugin built against
# other headers (an older or newer SDK, a changed class layout) is refused before it is loaded.
# Run at build time (cmake -P) whenever a header changes:
#   -DOUT=<.../pathlet/sdk_fingerprint.hpp> -DHEADERS=<a;b;c> (sorted by the caller)
set(text "")
foreach(h ${HEADERS})
  file(READ ${h} body)
  get_filename_component(name ${h} NAME)
  string(APPEND text "${name}\n${body}\n")
endforeach()
string(SHA256 hash "${text}")
string(SUBSTRING ${hash} 0 16 hash)
set(content "// Generated at build time by engine/sdk/cmake/sdk_fingerprint.cmake: the first 16 hex digits of
// the SHA-256 of the SDK headers. Every plugin exports the symbol PATHLET_SDK_SYMBOL; the host
// reads it from the plugin's ELF symbol table before loading it and refuses a plugin built
// against other headers (\"rebuild against this SDK\"). Installed with the SDK.
#pragma once
#define PATHLET_SDK_FINGERPRINT \"${hash}\"
#define PATHLET_SDK_SYMBOL pathlet_sdk_${hash}
")
# Rewritten only when it changes, so an unchanged SDK rebuilds nothing.
if(EXISTS ${OUT})
  file(READ ${OUT} old)
  if(old STREQUAL content)
    return()
  endif()
endif()
file(WRITE ${OUT} "${content}")
