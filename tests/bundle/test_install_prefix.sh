#!/usr/bin/env bash
# `cmake --install BUILD --prefix P` stays inside P: every file it lists is under P, nothing new
# appears where the Python package used to go (the interpreter's site-packages) or in HOME, and
# `import pathlet` from P's site-packages finds libpathlet in P through its RPATH and renders.
set -euo pipefail
BUILD=$1 SRC=$2 WORK=$3
rm -rf "$WORK"
mkdir -p "$WORK/home"
P=$WORK/prefix
PY=/usr/bin/python3
watched=(/usr/local /usr/lib/python3/dist-packages)
mapfile -t -O 2 watched < <($PY -c 'import site, sysconfig; print(*site.getsitepackages(), sysconfig.get_path("platlib"), sep="\n")')
touch "$WORK/stamp"
HOME=$WORK/home cmake --install "$BUILD" --prefix "$P" >"$WORK/install.log"
outside=$(grep -v "^$P/" "$BUILD/install_manifest.txt" || true)
[ -z "$outside" ] || { echo "FAIL: installed outside the prefix:"; echo "$outside"; exit 1; }
for d in "${watched[@]}"; do
  [ -d "$d" ] || continue
  new=$(find "$d" -newer "$WORK/stamp" -not -type d 2>/dev/null | head -5)
  [ -z "$new" ] || { echo "FAIL: the install wrote into $d:"; echo "$new"; exit 1; }
done
[ -z "$(ls -A "$WORK/home")" ] || { echo "FAIL: the install wrote into HOME"; ls -A "$WORK/home"; exit 1; }
site=$(echo "$P"/lib/python3*/site-packages)
test -f "$site/pathlet/__init__.py" || { echo "FAIL: no pathlet package under $P/lib/python3*/site-packages"; exit 1; }
grep -q "PYTHONPATH=$site for import pathlet" "$WORK/install.log" || { echo "FAIL: the install does not say the PYTHONPATH"; exit 1; }
module=$(echo "$site"/pathlet/_pathlet*.so)
readelf -d "$module" | grep -q 'R.*PATH.*\[\$ORIGIN/\.\./\.\./\.\.\]' || { readelf -d "$module" | grep PATH; echo "FAIL: RPATH"; exit 1; }
resolved=$(ldd "$module" | awk '$1 == "libpathlet.so.0" { print $3 }')
[ -n "$resolved" ] && [ "$(realpath "$resolved")" = "$(realpath "$P/lib/libpathlet.so.0")" ] ||
  { echo "FAIL: the module finds libpathlet at '$resolved', not in the prefix"; exit 1; }
env -i HOME="$WORK/home" PYTHONPATH="$site" $PY - "$P" "$SRC/tests/engine/data/two_lines.vtk" <<'PYEOF'
import sys
import pathlet
prefix, data = sys.argv[1:]
assert pathlet.__file__.startswith(prefix + "/"), pathlet.__file__
frame = pathlet.render("variant1_lineao", pathlet.load(data), time=1, size=(64, 48)).rgba
assert frame.shape == (48, 64, 4) and (frame[..., :3] < 200).any(), "lines drawn"
print("import pathlet from", prefix, "renders")
PYEOF
