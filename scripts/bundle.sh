#!/usr/bin/env bash
# A relocatable Pathlet for clusters and containers: one tarball that runs wherever
# it is unpacked, for any user, without root, apt or environment variables.
#   scripts/bundle.sh [--lean] [--from BUILD] OUT.tar.xz|OUT_DIR [-- CMAKE_ARGS...]
#     --lean        built without OpenImageIO (PNG through stb; EXR refused), Embree (no ray-traced
#                   quality reference) and HDF5 (no 4DFlowNet .h5 volumes): PATHLET_LEAN=ON
#     --from BUILD  pack an existing configured and built tree (its options decide lean or not)
#                   instead of building build-bundle[-lean]/ (tests off) first
#     OUT_DIR       a folder instead of a tarball: the bundle unpacked, in OUT_DIR/pathlet-VERSION[-lean]
#     CMAKE_ARGS    extra configure arguments for that build (e.g. a compiler launcher)
#   PATHLET_BUNDLE_XZ  xz options (default -9 -T0)
# Inside, under pathlet-VERSION[-lean]/:
#   bin/pathlet        the launcher: runs libexec/pathlet with the bundle's libraries
#   bin/pathlet-env    eval "$(bin/pathlet-env)": PATH and PYTHONPATH for the shell and `import pathlet`
#   libexec/pathlet    the command
#   lib/               libpathlet, the pass plugins (lib/pathlet/passes), every shared library these
#                      need beyond glibc and the GL/EGL driver (RUNPATH $ORIGIN), lib/python3.X/site-packages
#   lib/compat/SONAME/ the libraries a GL driver loads too (C++ runtime, libdrm, zlib, X11/xcb, ...):
#                      the node's copy when it has one, so its driver gets the version it was built
#                      for; the bundle's where the node has none or the command needs newer (pathlet-env)
#   share/pathlet/     shaders, graphs, fonts (DejaVu Sans + licence), bundle.txt (what this is),
#                      libraries.txt (each bundled library with its Debian package and version)
#   share/doc/PKG/copyright   the licence of every bundled library's package
#   include/, lib/cmake/      the SDK, to build plugins against the bundle
# Not inside: glibc (the node needs glibc >= the version bundle.txt names) and the GL/EGL driver:
# glvnd's libEGL/libOpenGL/libGLX/libGLdispatch and the vendor's driver come from the node.
set -euo pipefail
cd "$(dirname "$0")/.."
SRC=$PWD
usage() { sed -n '2,11p' "$0" | sed 's/^# \{0,1\}//'; }
LEAN=0 FROM="" OUT="" CMAKE_ARGS=()
while [ $# -gt 0 ]; do
  case "$1" in
    --lean) LEAN=1 ;;
    --from) [ $# -ge 2 ] || { echo "bundle: --from needs a build folder" >&2; exit 2; }; FROM=$2; shift ;;
    -h|--help) usage; exit 0 ;;
    --) shift; CMAKE_ARGS=("$@"); break ;;
    -*) echo "bundle: unknown option '$1'" >&2; usage >&2; exit 2 ;;
    *) [ -z "$OUT" ] || { echo "bundle: one output file, not '$OUT' and '$1'" >&2; exit 2; }; OUT=$1 ;;
  esac
  shift
done
case "$OUT" in
  "") echo "bundle: which file? (scripts/bundle.sh [--lean] OUT.tar.xz)" >&2; exit 2 ;;
  *.tar.xz) ;;
  *.tar|*.tgz|*.gz|*.zip|*.tar.*) echo "bundle: '$OUT': a bundle is a .tar.xz file (or a folder)" >&2; exit 2 ;;
  *) [ ! -e "$OUT" ] || [ -d "$OUT" ] || { echo "bundle: '$OUT' exists and is not a folder" >&2; exit 2; } ;;
esac
OUT=$(realpath -m "$OUT")
for tool in patchelf ldd dpkg-query objdump xz; do
  command -v "$tool" >/dev/null || { echo "bundle: '$tool' not found (scripts/install-deps.sh installs it)" >&2; exit 1; }
done

cache() { sed -n "s/^$1:[A-Z]*=//p" "$BUILD/CMakeCache.txt"; }
if [ -n "$FROM" ]; then
  BUILD=$(realpath "$FROM")
  [ -f "$BUILD/CMakeCache.txt" ] || { echo "bundle: '$FROM' is not a configured build folder" >&2; exit 1; }
else
  BUILD=$SRC/build-bundle
  [ "$LEAN" = 1 ] && BUILD=$SRC/build-bundle-lean
  echo "bundle: building $(basename "$BUILD")/ (Release, no tests)"
  cmake -S "$SRC" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DPATHLET_BUILD_TESTS=OFF -DPATHLET_BUILD_BENCHMARKS=OFF \
    -DPATHLET_LEAN=$([ "$LEAN" = 1 ] && echo ON || echo OFF) "${CMAKE_ARGS[@]}" >/dev/null
  cmake --build "$BUILD" -j"$(nproc)" >"$BUILD/bundle-build.log" 2>&1 ||
    { tail -30 "$BUILD/bundle-build.log" >&2; echo "bundle: the build failed (log: $BUILD/bundle-build.log)" >&2; exit 1; }
fi
# What the tree is decides the name: lean when any optional part is left out.
variant=default
for f in OPENIMAGEIO EMBREE HDF5; do [ "$(cache PATHLET_WITH_$f)" = ON ] || variant=lean; done
if [ "$LEAN" = 1 ] && [ "$variant" != lean ]; then
  echo "bundle: --lean, but $BUILD is a full build (configure it with -DPATHLET_LEAN=ON)" >&2; exit 1
fi
[ "$(cache CMAKE_INSTALL_LIBDIR)" = lib ] ||
  { echo "bundle: $BUILD installs libraries into '$(cache CMAKE_INSTALL_LIBDIR)', the bundle expects lib" >&2; exit 1; }
PYTHONDIR=$(cache PATHLET_INSTALL_PYTHONDIR)
[ -n "$PYTHONDIR" ] || { echo "bundle: $BUILD has no Python module (PATHLET_BUILD_PYTHON=OFF?)" >&2; exit 1; }
VERSION=$(sed -n 's/^CMAKE_PROJECT_VERSION:[A-Z]*=//p' "$BUILD/CMakeCache.txt")
NAME=pathlet-${VERSION:-0}
[ "$variant" = lean ] && NAME=$NAME-lean

WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
B=$WORK/$NAME
if [ "${OUT%.tar.xz}" = "$OUT" ]; then  # a folder: staged in place
  B=$OUT/$NAME
  [ ! -e "$B" ] || { echo "bundle: $B exists already" >&2; exit 1; }
  mkdir -p "$OUT"
fi
cmake --install "$BUILD" --prefix "$B" >"$WORK/install.log"
mkdir -p "$B/libexec" "$B/lib/compat"
mv "$B/bin/pathlet" "$B/libexec/pathlet"
python_version=$(basename "$(dirname "$PYTHONDIR")" | sed 's/^python//')
sed -e "s|@PYTHONDIR@|$PYTHONDIR|" -e "s|@PYTHON_VERSION@|$python_version|" scripts/bundle/pathlet-env >"$B/bin/pathlet-env"
cp scripts/bundle/pathlet "$B/bin/pathlet"
chmod 755 "$B/bin/pathlet" "$B/bin/pathlet-env"

# Our ELF files: the command, libpathlet, the plugins, the Python module.
mapfile -t ours < <(find "$B/libexec" "$B/lib" -type f \( -name pathlet -o -name '*.so' -o -name '*.so.*' \) | sort)
# Every library they load (ldd: the whole closure), resolved on this machine.
declare -A soname_at=()
for f in "${ours[@]}"; do
  while read -r name arrow path _; do
    [ "$arrow" = "=>" ] || continue
    [ "$path" = "not" ] && { echo "bundle: $f needs $name, which is not found here" >&2; exit 1; }
    case "$path" in "$B"/*) continue ;; esac
    soname_at[$path]=$name
  done < <(ldd "$f")
done
declare -A need=()  # real file -> soname
mapfile -t real < <(realpath "${!soname_at[@]}")
i=0
for path in "${!soname_at[@]}"; do need[${real[$i]}]=${soname_at[$path]}; i=$((i + 1)); done
# Which Debian package each comes from (dpkg's file lists, in one pass; with merged /usr a file is
# registered under /lib or /usr/lib): glibc and glvnd stay the node's.
declare -A pkg_of=()
for f in "${!need[@]}"; do printf '%s\n%s\n' "$f" "${f#/usr}"; done >"$WORK/asked.txt"
while IFS= read -r line; do  # /var/lib/dpkg/info/PKG[:ARCH].list:FILE
  file=${line#*.list:}
  pkg=$(basename "${line%%.list:*}")
  pkg_of[/usr${file#/usr}]=${pkg%%:*}
done < <(grep -F -x -H -f "$WORK/asked.txt" /var/lib/dpkg/info/*.list || true)
NODE_PACKAGES=" libc6 libegl1 libopengl0 libglx0 libgldispatch0 libgl1 libgles2 libglvnd0 "
# What GL drivers (Mesa, NVIDIA's EGL) link too: loaded once per process, so the node's copy wins
# where the node has one (a driver may need it newer than ours), ours where it has none.
NODE_FIRST=" libstdc++6 libgcc-s1 libdrm2 libexpat1 zlib1g libzstd1 libelf1 libffi8 libxml2 liblzma5 libx11-6 
  libx11-xcb1 libxau6 libxdmcp6 libbsd0 libmd0 libxext6 libxfixes3 libxshmfence1 libwayland-client0 "
: >"$WORK/libraries.txt"
declare -A docs=()
in_lib=() in_compat=()
for path in $(printf '%s\n' "${!need[@]}" | sort); do
  name=${need[$path]} pkg=${pkg_of[$path]:-}
  [ -n "$pkg" ] || { echo "bundle: $path ($name) belongs to no Debian package; cannot tell whether to bundle it" >&2; exit 1; }
  case "$NODE_PACKAGES" in *" $pkg "*) continue ;; esac
  dest=$B/lib/$name
  case "$NODE_FIRST" in *" $pkg "*) dest=$B/lib/compat/$name/$name ;; esac
  case "$pkg" in libxcb*) dest=$B/lib/compat/$name/$name ;; esac
  mkdir -p "$(dirname "$dest")"
  cp -L "$path" "$dest"
  if [ "$dest" = "$B/lib/$name" ]; then in_lib+=("$dest"); else in_compat+=("$dest"); fi
  printf '%s\t%s\n' "${dest#$B/}" "$pkg" >>"$WORK/libraries.txt"
  docs[$pkg]=1
done
chmod 644 "${in_lib[@]}" "${in_compat[@]}"
patchelf --set-rpath '$ORIGIN' "${in_lib[@]}"
[ ${#in_compat[@]} -eq 0 ] || patchelf --set-rpath '$ORIGIN/../..' "${in_compat[@]}"
# Each with its package's version (one query).
declare -A version_of=()
while read -r p v; do version_of[$p]=$v; done < <(dpkg-query -W -f='${Package} ${Version}\n' "${!docs[@]}")
while IFS=$'\t' read -r file pkg; do printf '%s\t%s\t%s\n' "$file" "$pkg" "${version_of[$pkg]:-}"; done \
  <"$WORK/libraries.txt" | sort >"$B/share/pathlet/libraries.txt"
for pkg in "${!docs[@]}"; do
  for doc in /usr/share/doc/"$pkg"/copyright /usr/share/doc/"${pkg%%:*}"/copyright; do
    [ -f "$doc" ] && { mkdir -p "$B/share/doc/$pkg"; cp "$doc" "$B/share/doc/$pkg/copyright"; break; }
  done
done
strip --strip-unneeded "${ours[@]}"

# The oldest glibc the node may have: the newest GLIBC_ symbol version anything here needs.
glibc=$(find "$B/libexec" "$B/lib" -type f \( -name pathlet -o -name '*.so*' \) -exec objdump -T {} + 2>/dev/null |
  grep -o 'GLIBC_[0-9][0-9.]*' | sed 's/GLIBC_//' | sort -uV | tail -1)
commit=$(git -C "$SRC" describe --always --dirty 2>/dev/null || echo unknown)
os=$(. /etc/os-release && echo "$PRETTY_NAME")
echo "pathlet bundle ($variant) $VERSION, $commit, made $(date -u +%F) on $os; needs glibc >= $glibc and a GL 4.5 driver (EGL)" \
  >"$B/share/pathlet/bundle.txt"

if [ "$B" = "$WORK/$NAME" ]; then
  tar -C "$WORK" --owner=0 --group=0 --numeric-owner --sort=name -cf - "$NAME" |
    xz ${PATHLET_BUNDLE_XZ:--9 -T0} >"$OUT.tmp"
  mv "$OUT.tmp" "$OUT"
  packed=$(stat -c %s "$OUT")
else
  OUT=$B packed=0
fi
awk -v out="$OUT" -v variant="$variant" -v packed="$packed" -v unpacked="$(du -sb "$B" | cut -f1)" \
    -v libs="$(wc -l <"$B/share/pathlet/libraries.txt")" -v compat="$(grep -c '^lib/compat/' "$B/share/pathlet/libraries.txt" || true)" \
    -v glibc="$glibc" 'BEGIN { printf "bundle: %s (%s): %s%.1f MiB unpacked, %d libraries bundled (%d in lib/compat), glibc >= %s\n", out, variant, packed ? sprintf("%.1f MiB compressed, ", packed / 1048576) : "", unpacked / 1048576, libs, compat, glibc }'
