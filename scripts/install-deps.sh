#!/usr/bin/env bash
# Installs the Debian 12 packages Pathlet needs that are not installed yet (root or sudo).
#   --slurm   also a single-node Slurm (slurm-wlm, munge) for tests/slurm; not in the main job
set -euo pipefail
SLURM=0
for arg in "$@"; do
  case "$arg" in
    --slurm) SLURM=1 ;;
    *) echo "install-deps: unknown option '$arg' (--slurm)" >&2; exit 2 ;;
  esac
done
PKGS=(
  build-essential cmake pkg-config ccache           # toolchain (ccache: the lean bundle's test reuses objects)
  libegl-dev libopengl-dev libegl-mesa0 libgl1-mesa-dri   # GL 4.5 via EGL; llvmpipe when there is no GPU
  libglfw3-dev libglm-dev nlohmann-json3-dev libtinygltf-dev
  libopenimageio-dev openimageio-tools              # image files (tools: OIIO's CMake targets expect them)
  libfreetype-dev fonts-dejavu-core                 # the overlay's text (time label, legend)
  zlib1g-dev libhdf5-dev                            # .vtp/.vti zlib blocks; 4D flow HDF5 volumes
  libgtest-dev libbenchmark-dev                     # tests and benchmarks
  libembree-dev                                     # ray-traced AO reference of `pathlet quality` (Embree 3)
  xvfb                                              # window tests of `pathlet view` (private X server)
  libimgui-dev libstb-dev                           # the panels of `pathlet view` (Dear ImGui); stb: PNG in a
                                                    # lean build, the overlay's built-in font
  patchelf                                          # scripts/bundle.sh: RUNPATH $ORIGIN on bundled libraries
  python3-numpy python3-pil                         # figure scripts (scripts/aa-figures.sh, real-data-sheet.sh)
  python3-dev pybind11-dev python3-pybind11         # import pathlet (engine/apps/python)
  python3-matplotlib python3-pytest                 # pathlet.plot, bench --plots; the module's tests
  jupyter-nbconvert python3-ipykernel               # the example notebook, executed by the tests
  clang-14 libclang-rt-14-dev llvm-14               # sanitizer build and libFuzzer targets (scripts/sanitize.sh, fuzz.sh)
)
OPTIONAL=(ffmpeg python3-pandas)                    # MP4 export; DataFrames from pathlet (else lists of dicts)
[ "$SLURM" = 1 ] && PKGS+=(slurm-wlm munge)         # tests/slurm: slurmctld + slurmd on localhost
# In CI (CI set, not false/0) the optional ones are required: a test that needs one fails there
# instead of skipping (tests/support/optional_tool.sh).
case "${CI:-}" in ""|false|0) ;; *) PKGS+=("${OPTIONAL[@]}"); OPTIONAL=() ;; esac
missing=()
for p in "${PKGS[@]}" "${OPTIONAL[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: everything is installed"
  exit 0
fi
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${PKGS[@]}" >/dev/null
[ ${#OPTIONAL[@]} -eq 0 ] || $SUDO apt-get install -y -qq --no-install-recommends "${OPTIONAL[@]}" >/dev/null 2>&1 \
  || echo "install-deps: ffmpeg or python3-pandas not installed; videos are skipped (image sequences still work),
  pathlet tables are lists of dicts"
