#!/usr/bin/env bash
# Installs Pathlet into a temporary prefix, builds plugins/example_vignette against that SDK
# only (a separate CMake project), and renders a graph that uses the out-of-tree pass.
set -euo pipefail
BUILD=$1 SRC=$2 WORK=$3
rm -rf "$WORK"
mkdir -p "$WORK"
cmake --install "$BUILD" --prefix "$WORK/prefix" >"$WORK/install.log"
cmake -S "$SRC/plugins/example_vignette" -B "$WORK/plugin" -DCMAKE_PREFIX_PATH="$WORK/prefix" \
      -DCMAKE_BUILD_TYPE=Release >"$WORK/configure.log"
cmake --build "$WORK/plugin" >"$WORK/build.log"
PATHLET="$WORK/prefix/bin/pathlet"
"$PATHLET" passes --plugin-dir "$WORK/plugin" | tee "$WORK/passes.txt" | grep -q "^vignette "
"$PATHLET" passes --describe vignette --plugin-dir "$WORK/plugin" | grep -q "strength (float"
"$PATHLET" render "$SRC/plugins/example_vignette/vignette_demo.json" --plugin-dir "$WORK/plugin" \
  --data "$SRC/tests/engine/data/two_lines.vtk" --time 0 --size 64x48 --out "$WORK/out" --quiet >"$WORK/render.log"
test -s "$WORK/out/vignette_demo/00000.png"
# Without the plugin folder the graph names an unknown pass type: exit 1, with the pointer.
if "$PATHLET" validate "$SRC/plugins/example_vignette/vignette_demo.json" 2>"$WORK/validate.err"; then
  echo "validate should fail without the plugin"; exit 1
fi
grep -q "/passes/1/type" "$WORK/validate.err"
echo "sdk: installed, built the example plugin out of tree, rendered with it"
