#!/usr/bin/env bash
# Unpacks a bundle (scripts/bundle.sh) into a fresh folder and uses it as a plain user on a node
# would: a clean environment (env -i, only HOME), as user nobody when run as root (the bundle is
# then read-only to it), from a folder the build never knew.
#   check_bundle.sh TARBALL|FOLDER SRC WORK default|lean [REFERENCE_PATHLET]   (FOLDER: bundle.sh's folder output)
# Checks: --version says bundle and variant; render and validate work; the picture is the one
# REFERENCE_PATHLET (the build tree's command) renders, byte for byte; `import pathlet` through
# pathlet-env's PYTHONPATH renders the same picture; nothing loads from outside the bundle but
# glibc, the C++ runtime and the GL driver; the font and its licence are inside. Lean: EXR, the
# ray-traced quality reference and HDF5 are refused, naming the file or the feature.
set -euo pipefail
TARBALL=$1 SRC=$2 WORK=$3 VARIANT=$4 REFERENCE=${5:-}
rm -rf "$WORK"
mkdir -p "$WORK/unpacked" "$WORK/user"
if [ -d "$TARBALL" ]; then
  B=$(echo "$TARBALL"/pathlet-*)
else
  tar -C "$WORK/unpacked" -xf "$TARBALL"
  B=$(echo "$WORK"/unpacked/pathlet-*)
fi
[ -x "$B/bin/pathlet" ] || { echo "no bin/pathlet in $TARBALL"; exit 1; }
DATA=$SRC/tests/engine/data/two_lines.vtk
fail() { echo "FAIL: $*"; exit 1; }
# Same pixels (the lean build's PNG encoder is stb's, so the bytes may differ).
same_pixels() {
  /usr/bin/python3 -c 'import sys, numpy as np; from PIL import Image
a, b = (np.asarray(Image.open(p).convert("RGBA")) for p in sys.argv[1:])
sys.exit(0 if a.shape == b.shape and np.array_equal(a, b) else 1)' "$1" "$2"
}

AS_USER=()
if [ "$(id -u)" = 0 ]; then  # a plain user: nobody, who may read the bundle but not write it
  chmod -R a+rX "$B"
  chown nobody:nogroup "$WORK/user"
  AS_USER=(setpriv --reuid=nobody --regid=nogroup --clear-groups)
fi
run() { "${AS_USER[@]}" env -i HOME="$WORK/user" "$@"; }

# What it is, from where.
run "$B/bin/pathlet" --version >"$WORK/version.txt"
cat "$WORK/version.txt"
grep -q "^runs from a bundle: $B (pathlet bundle ($VARIANT)" "$WORK/version.txt" || fail "--version does not say the bundle"
if [ "$VARIANT" = lean ]; then
  grep -q "^build: lean: PNG through stb, without OpenImageIO, Embree, HDF5" "$WORK/version.txt" || fail "not a lean build"
else
  grep -q "^build: full (OpenImageIO, Embree, HDF5)" "$WORK/version.txt" || fail "not a full build"
fi
test -f "$B/share/pathlet/fonts/DejaVuSans.ttf" && test -f "$B/share/pathlet/fonts/LICENSE-DejaVu.txt" ||
  fail "the label font or its licence is missing"

# On a node that has none of lib/compat's libraries (all of them on the library path), nothing
# comes from outside the bundle but glibc and glvnd's GL/EGL.
all_compat=$(find "$B/lib/compat" -mindepth 1 -maxdepth 1 -type d | sort | paste -sd:)
[ -n "$all_compat" ] || fail "no lib/compat"
for f in "$B/libexec/pathlet" "$B"/lib/libpathlet.so.* "$B"/lib/pathlet/passes/*.so "$B"/lib/python3*/site-packages/pathlet/*.so; do
  [ -L "$f" ] && continue
  LD_LIBRARY_PATH=$all_compat ldd "$f" | awk '$2 == "=>" { print $1, $3 }' | while read -r name path; do
    case "$path" in
      "$B"/*) ;;
      *) case "$name" in
           libc.so.*|libm.so.*|libdl.so.*|libpthread.so.*|librt.so.*|libresolv.so.*|ld-linux*) ;;
           libEGL.so.*|libOpenGL.so.*|libGLX.so.*|libGLdispatch.so.*|libGL.so.*) ;;
           *) echo "FAIL: $(basename "$f") loads $name from $path, outside the bundle"; exit 1 ;;
         esac ;;
    esac
  done
done
! grep -E "^lib/(compat/[^/]*/)?(libEGL|libOpenGL|libGLX|libGLdispatch|libc)\.so" "$B/share/pathlet/libraries.txt" || fail "glibc or glvnd bundled"

# validate and render, as the user.
run "$B/bin/pathlet" validate "$B"/share/pathlet/graphs/*.json >"$WORK/validate.txt" 2>&1 || { cat "$WORK/validate.txt"; fail "validate"; }
run "$B/bin/pathlet" render variant1_lineao --data "$DATA" --time 1 --size 96x64 --out "$WORK/user/out" --quiet \
  >"$WORK/render.txt" 2>&1 || { cat "$WORK/render.txt"; fail "render"; }
PNG=$WORK/user/out/variant1_lineao/00000.png
test -s "$PNG" || fail "no picture"
! grep -q "warning" "$WORK/render.txt" || { cat "$WORK/render.txt"; fail "warnings in a plain render"; }
if [ -n "$REFERENCE" ]; then
  env -i HOME="$WORK/user" "$REFERENCE" render variant1_lineao --data "$DATA" --time 1 --size 96x64 \
    --out "$WORK/reference" --quiet >"$WORK/reference.txt" 2>&1 || { cat "$WORK/reference.txt"; fail "the reference render ($REFERENCE)"; }
  same_pixels "$PNG" "$WORK/reference/variant1_lineao/00000.png" || fail "the bundle's picture differs from the build tree's"
fi
# A node that has none of lib/compat's libraries: the bundle's copies load and give the same picture.
run LD_LIBRARY_PATH="$all_compat" "$B/libexec/pathlet" render variant1_lineao --data "$DATA" --time 1 --size 96x64 \
  --out "$WORK/user/compat" --quiet >"$WORK/compat.txt" 2>&1 || { cat "$WORK/compat.txt"; fail "render with lib/compat"; }
same_pixels "$PNG" "$WORK/user/compat/variant1_lineao/00000.png" || fail "lib/compat's libraries change the picture"
[ -z "$(run "$B/bin/pathlet-env" --ld-library-path)" ] || fail "this machine has every lib/compat library, yet pathlet-env adds some"

# import pathlet from the bundle: the folder pathlet-env prints, no other setup.
PYTHONPATH_B=$(run "$B/bin/pathlet-env" --pythonpath)
[ "$PYTHONPATH_B" = "$(echo "$B"/lib/python3*/site-packages)" ] || fail "pathlet-env --pythonpath says '$PYTHONPATH_B'"
eval "$(run "$B/bin/pathlet-env" 2>/dev/null)"  # the documented way: PATH and PYTHONPATH
[ "$(command -v pathlet)" = "$B/bin/pathlet" ] || fail "pathlet-env does not put bin/ on PATH"
run PYTHONPATH="$PYTHONPATH_B" /usr/bin/python3 - "$B" "$DATA" "$PNG" <<'EOF' || fail "import pathlet from the bundle"
import sys
import numpy as np
from PIL import Image
import pathlet
bundle, data, png = sys.argv[1:]
assert pathlet.__file__.startswith(bundle + "/"), pathlet.__file__
info = pathlet.build_info()
assert "runs from a bundle: " + bundle in info, info
frame = pathlet.render("variant1_lineao", pathlet.load(data), time=1, size=(96, 64)).rgba
cli = np.asarray(Image.open(png).convert("RGBA"))
assert frame.shape == cli.shape and np.array_equal(frame, cli), "Python's frame differs from the command's"
assert (frame[..., :3] < 200).any(), "the lines are drawn"
print("import pathlet from the bundle: the command's picture")
EOF

if [ "$VARIANT" = lean ]; then
  # EXR refused with the file named, nothing half-written (lineao_debug captures .exr maps).
  if run "$B/bin/pathlet" render lineao_debug --data "$DATA" --time 1 --size 64x48 --out "$WORK/user/exr" --quiet \
       >"$WORK/exr.txt" 2>&1; then fail "lineao_debug's EXR captures were written by a lean build"; fi
  cat "$WORK/exr.txt"
  grep -q "$WORK/user/exr/lineao_debug/.*\.exr: cannot write image: this build has no EXR" "$WORK/exr.txt" || fail "EXR message"
  ! find "$WORK/user/exr" -name '*.exr' -o -name '.*tmp*' | grep -q . || fail "EXR or temp files left"
  if run "$B/bin/pathlet" quality variant1_vao --data "$DATA" --time 0:1:0.5 --size 32x24 >"$WORK/quality.txt" 2>&1; then
    fail "quality ran without Embree"
  fi
  grep -q "ray-traced AO reference of quality is not in this build" "$WORK/quality.txt" || { cat "$WORK/quality.txt"; fail "quality message"; }
  printf '\x89HDF\r\n\x1a\n' >"$WORK/user/flow.h5"
  if run "$B/bin/pathlet" trace "$WORK/user/flow.h5" -o "$WORK/user/flow.vtp" >"$WORK/trace.txt" 2>&1; then fail "trace read HDF5"; fi
  grep -q "flow.h5: byte 0: this build has no HDF5" "$WORK/trace.txt" || { cat "$WORK/trace.txt"; fail "HDF5 message"; }
fi
echo "bundle ($VARIANT) OK: $(du -sh "$B" | cut -f1) unpacked, $(wc -l <"$B/share/pathlet/libraries.txt") libraries"
