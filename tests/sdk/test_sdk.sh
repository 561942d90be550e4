#!/usr/bin/env bash
# Installs Pathlet into a temporary prefix, builds plugins/example_vignette (a full-screen pass)
# and plugins/example_fade (a fade strategy on the line kit) against that SDK only (separate
# CMake projects), and renders graphs that use the out-of-tree passes.
set -euo pipefail
BUILD=$1 SRC=$2 WORK=$3
rm -rf "$WORK"
mkdir -p "$WORK"
cmake --install "$BUILD" --prefix "$WORK/prefix" >"$WORK/install.log"
cmake -S "$SRC/plugins/example_vignette" -B "$WORK/plugin" -DCMAKE_PREFIX_PATH="$WORK/prefix" \
      -DCMAKE_BUILD_TYPE=Release >"$WORK/configure.log"
cmake --build "$WORK/plugin" >"$WORK/build.log"
PATHLET="$WORK/prefix/bin/pathlet"
"$PATHLET" passes --plugin-dir "$WORK/plugin" >"$WORK/passes.txt"
grep -q "^vignette " "$WORK/passes.txt"
"$PATHLET" passes --describe vignette --plugin-dir "$WORK/plugin" >"$WORK/vignette.txt"
grep -q "strength (float" "$WORK/vignette.txt"
"$PATHLET" render "$SRC/plugins/example_vignette/vignette_demo.json" --plugin-dir "$WORK/plugin" \
  --data "$SRC/tests/engine/data/two_lines.vtk" --time 0 --size 64x48 --out "$WORK/out" --quiet >"$WORK/render.log"
test -s "$WORK/out/vignette_demo/00000.png"
# Without the plugin folder the graph names an unknown pass type: exit 1, with the pointer.
if "$PATHLET" validate "$SRC/plugins/example_vignette/vignette_demo.json" 2>"$WORK/validate.err"; then
  echo "validate should fail without the plugin"; exit 1
fi
grep -q "/passes/1/type" "$WORK/validate.err"
grep -q "plugin-dir" "$WORK/validate.err"

# The line kit is installed: header, shaders, pass READMEs.
test -f "$WORK/prefix/include/pathlet/lines.hpp"
test -f "$WORK/prefix/share/pathlet/shaders/line_hooks.glsl"
test -f "$WORK/prefix/lib/pathlet/passes/pathlet_gbuffer/README.md"
! grep -l "shared/" "$WORK"/prefix/lib/pathlet/passes/*/README.md
test -f "$WORK/prefix/include/pathlet/sdk_fingerprint.hpp"

# A plugin built against another SDK (its installed fingerprint differs) is refused from its
# symbol table, before it is loaded: "rebuild against this SDK".
cp -r "$WORK/prefix" "$WORK/old-prefix"
sed -i 's/#define PATHLET_SDK_FINGERPRINT "[0-9a-f]*"/#define PATHLET_SDK_FINGERPRINT "00000000000000aa"/;
        s/#define PATHLET_SDK_SYMBOL pathlet_sdk_[0-9a-f]*/#define PATHLET_SDK_SYMBOL pathlet_sdk_00000000000000aa/' \
  "$WORK/old-prefix/include/pathlet/sdk_fingerprint.hpp"
cmake -S "$SRC/plugins/example_vignette" -B "$WORK/old-plugin" -DCMAKE_PREFIX_PATH="$WORK/old-prefix" \
      -DCMAKE_BUILD_TYPE=Release >"$WORK/old-configure.log"
cmake --build "$WORK/old-plugin" >"$WORK/old-build.log"
if "$PATHLET" passes --plugin-dir "$WORK/old-plugin" >"$WORK/old-passes.txt" 2>"$WORK/old-passes.err"; then
  echo "a plugin of another SDK should be refused"; exit 1
fi
grep -q "rebuild against this SDK" "$WORK/old-passes.err"
! grep -q "^vignette " "$WORK/old-passes.txt"

# A fade strategy built out of tree against the kit, rendered through LineAO.
cmake -S "$SRC/plugins/example_fade" -B "$WORK/fade" -DCMAKE_PREFIX_PATH="$WORK/prefix" \
      -DCMAKE_BUILD_TYPE=Release >"$WORK/fade-configure.log"
cmake --build "$WORK/fade" >"$WORK/fade-build.log"
"$PATHLET" passes --describe desaturate_fade --plugin-dir "$WORK/fade" >"$WORK/desaturate.txt"
grep -q "start (float" "$WORK/desaturate.txt"
# It replaces variant 1's gbuffer pass through a graph that extends the installed variant 1.
"$PATHLET" render "$SRC/plugins/example_fade/desaturate_v1.json" --plugin-dir "$WORK/fade" \
  --data "$SRC/tests/engine/data/two_lines.vtk" --time 1 --size 96x64 --out "$WORK/out" --quiet >"$WORK/fade-render.log"
test -s "$WORK/out/desaturate_v1/00000.png"

# The GLSL route: a fade strategy as one file, no build, in graphs extending variants 1 and 2.
for g in speed_fade_v1 speed_fade_oit; do
  "$PATHLET" render "$SRC/plugins/example_fade/$g.json" --data "$SRC/tests/engine/data/two_lines.vtk" --time 1 \
    --size 96x64 --out "$WORK/out" --quiet >"$WORK/$g.log"
  test -s "$WORK/out/$g/00000.png"
done
"$PATHLET" passes --describe fill_list >"$WORK/fill_list.txt"  # (grep -q on a pipe: SIGPIPE under pipefail)
grep -q "tail_fade (float, default 0.5, range \[0, 1\], from line_fade.glsl)" "$WORK/fill_list.txt"
echo "sdk: installed, built both example plugins out of tree, rendered with them and with the GLSL fade strategy"
