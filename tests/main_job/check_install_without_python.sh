#!/usr/bin/env bash
# After the main job (scripts/main.sh builds pathlet_runtime, not the Python module) the
# README's `cmake --install build --prefix DIR` must work: the Python rules install
# the package where the module was built and skip it, saying so, where it was not. The module
# of this (fully built) tree is hidden by pointing the generated Python rules at a file that is
# not there (the whole install with the module: bundle.install_prefix).
set -euo pipefail
BUILD=$1 SRC=$2 WORK=$3
rm -rf "$WORK" && mkdir -p "$WORK"
module=$(ls "$BUILD"/python/pathlet/_pathlet*.so 2>/dev/null | head -1 || true)
[ -n "$module" ] || module=$(find "$BUILD" -name '_pathlet*.so' -not -path '*/CMakeFiles/*' | head -1)
[ -n "$module" ] || { echo "skipped: no Python module built here to hide"; exit 77; }
rules=$BUILD/engine/apps/python/cmake_install.cmake
grep -q "$module" "$rules" || { echo "FAIL: $rules does not name $module"; exit 1; }
# The Python folder's rules as the main job's tree has them: the module's file is missing.
sed "s|$module|$WORK/not_built/$(basename "$module")|g" "$rules" > "$WORK/python_rules.cmake"
cmake -DCMAKE_INSTALL_PREFIX="$WORK/p" -P "$WORK/python_rules.cmake" > "$WORK/python.log" 2>&1 ||
  { cat "$WORK/python.log"; echo "FAIL: the Python install rules fail without the module"; exit 1; }
grep -q "Python: the module is not built" "$WORK/python.log" || { cat "$WORK/python.log"; echo "FAIL: the install does not say the module is missing"; exit 1; }
[ -z "$(find "$WORK/p" -name '*.py' 2>/dev/null)" ] || { echo "FAIL: a half package (the .py files without the module) was installed"; exit 1; }
# With the module: the package, the module and the PYTHONPATH line.
cmake -DCMAKE_INSTALL_PREFIX="$WORK/q" -P "$rules" > "$WORK/python_built.log" 2>&1 ||
  { cat "$WORK/python_built.log"; echo "FAIL: the Python install rules fail with the module"; exit 1; }
grep -q "PYTHONPATH=$WORK/q/" "$WORK/python_built.log" || { cat "$WORK/python_built.log"; echo "FAIL: no PYTHONPATH line"; exit 1; }
[ -n "$(find "$WORK/q" -name '_pathlet*.so')" ] && [ -n "$(find "$WORK/q" -name '__init__.py')" ] ||
  { echo "FAIL: the module or the package is missing from the install"; exit 1; }
echo "install: without the Python module it is skipped with a note; with it, the package and the module"
