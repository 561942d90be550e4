# Mirrors folders into the build tree's share folder: cmake -DDEST=dir -DSOURCES="a;b" -P this.
# file(COPY) keeps each file's timestamp and skips one whose copy has the same timestamp, so a
# rebuild rewrites only what changed, never a shader a running test is reading
# (`cmake -E copy_directory` rewrote every file on every build).
foreach(src IN LISTS SOURCES)
  file(COPY "${src}/" DESTINATION "${DEST}")
endforeach()
