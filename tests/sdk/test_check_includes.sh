#!/usr/bin/env bash
# check_includes.sh against small trees, one mistake each: the checker must fail naming the
# file, the line and the rule, and pass the same tree without the mistake.
#   tests/sdk/test_check_includes.sh CHECKER WORK
set -u
CHECK=$1 WORK=$2
rm -rf "$WORK"
mkdir -p "$WORK"
failed=0

# A tree with one file of each module, every include allowed.
make_tree() {
  local t=$1
  mkdir -p "$t"/engine/{base/include/pathlet,base/src,base/util,data/io,data/trace,sdk/include/pathlet,sdk/src}
  mkdir -p "$t"/engine/{lines/include/pathlet,lines/src,lines/tests,core/graph}
  mkdir -p "$t"/engine/apps/{common,cli,bench,quality,view,python} "$t"/passes/blur
  echo '#include <glm/glm.hpp>' >"$t/engine/base/include/pathlet/scene.hpp"
  echo '#include <pathlet/scene.hpp>' >"$t/engine/base/src/scene.cpp"
  printf '#include <nlohmann/json.hpp>\n#include "util/input_limits.hpp"\n' >"$t/engine/base/util/text.hpp"
  echo '#include <string>' >"$t/engine/base/util/input_limits.hpp"
  printf '#include <pathlet/scene.hpp>\n#include "util/text.hpp"\n' >"$t/engine/data/io/pathline_io.hpp"
  echo '#include <functional>' >"$t/engine/data/trace/progress.hpp"
  echo '#include "progress.hpp"' >"$t/engine/data/trace/tracer.hpp"  # its own folder's, not common/'s
  echo '#include <pathlet/scene.hpp>' >"$t/engine/sdk/include/pathlet/gpu_scene.hpp"
  printf '#include <pathlet/gpu_scene.hpp>\n#include <pathlet/scene.hpp>\n' >"$t/engine/sdk/src/gpu_scene.cpp"
  echo '#include <pathlet/gpu_scene.hpp>' >"$t/engine/lines/include/pathlet/lines.hpp"
  echo '#include <pathlet/lines.hpp>' >"$t/engine/lines/src/drawer.cpp"
  echo '#include "executor.hpp"' >"$t/engine/lines/tests/test_drawer.cpp"  # tests include anything
  printf '#include <pathlet/lines.hpp>\n#include "io/pathline_io.hpp"\n' >"$t/engine/core/executor.hpp"
  echo '#include "executor.hpp"' >"$t/engine/core/graph/compile.cpp"
  echo '#include <string>' >"$t/engine/core/runtime.hpp"
  printf '#include "runtime.hpp"\n#include "io/pathline_io.hpp"\n' >"$t/engine/apps/common/scene_source.hpp"
  echo '#include <string>' >"$t/engine/apps/common/progress.hpp"
  echo '#include "common/progress.hpp"' >"$t/engine/apps/cli/cmd_trace.cpp"
  echo '#include <string>' >"$t/engine/apps/cli/args.hpp"
  echo '#include "args.hpp"' >"$t/engine/apps/cli/cmd_render.cpp"
  echo '#include "common/scene_source.hpp"' >"$t/engine/apps/bench/run_experiment.cpp"
  echo '#include "runtime.hpp"' >"$t/engine/apps/quality/transparency.hpp"
  echo '#include "common/scene_source.hpp"' >"$t/engine/apps/view/viewer.hpp"
  echo '#include "view/viewer.hpp"' >"$t/engine/apps/cli/cmd_view.cpp"
  printf '#include "transparency.hpp"\n#include "common/scene_source.hpp"\n' >"$t/engine/apps/python/module.cpp"
  printf '#include <pathlet/scene.hpp>\n#include <pathlet/lines.hpp>\n' >"$t/passes/blur/blur.cpp"
}

# CASE NAME, FILE, the line to append to it, the message expected ("" for a clean tree).
expect() {
  local name=$1 file=$2 line=$3 want=$4
  local t="$WORK/$name"
  make_tree "$t"
  [ -z "$file" ] || { mkdir -p "$(dirname "$t/$file")"; echo "$line" >>"$t/$file"; }
  local out rc
  out=$(bash "$CHECK" "$t" 2>&1)
  rc=$?
  if [ -z "$want" ]; then
    if [ "$rc" = 0 ]; then echo "ok   $name"; else echo "FAIL $name: the clean tree failed (exit $rc):"; echo "$out"; failed=1; fi
    return
  fi
  local n
  n=$(wc -l <"$t/$file")
  if [ "$rc" = 0 ]; then
    echo "FAIL $name: passed; wanted '$file:$n: ...$want'"
    failed=1
  elif ! grep -qF -- "$file:$n: " <<<"$out" || ! grep -qF -- "$want" <<<"$out"; then
    echo "FAIL $name: wanted '$file:$n: ...$want', got:"
    echo "$out"
    failed=1
  else
    echo "ok   $name"
  fi
}

expect clean "" "" ""
expect data_up_to_sdk engine/data/io/pathline_io.hpp '#include <pathlet/gpu_scene.hpp>' \
  "includes engine/sdk/include/pathlet/gpu_scene.hpp: data may include only base"
expect base_up_to_data engine/base/util/text.hpp '#include "io/pathline_io.hpp"' \
  "base may include only std, GLM and JSON"
expect base_header_up_to_sdk engine/base/include/pathlet/scene.hpp '#include <pathlet/gpu_scene.hpp>' \
  "base may include only std, GLM and JSON"
expect sdk_up_to_core engine/sdk/src/gpu_scene.cpp '#include "runtime.hpp"' \
  "includes engine/core/runtime.hpp: sdk may include only base"
expect sdk_up_to_lines engine/sdk/include/pathlet/gpu_scene.hpp '#include <pathlet/lines.hpp>' \
  "sdk may include only base"
expect core_up_to_apps engine/core/graph/compile.cpp '#include "common/progress.hpp"' \
  "core may include only base data sdk lines"
expect bench_to_cli engine/apps/bench/run_experiment.cpp '#include "cli/args.hpp"' \
  "includes engine/apps/cli/args.hpp: only the pathlet command (engine/apps/cli) includes cli/"
expect python_to_cli_unprefixed engine/apps/python/module.cpp '#include "args.hpp"' \
  "includes engine/apps/cli/args.hpp: only the pathlet command (engine/apps/cli) includes cli/"
expect common_up_to_view engine/apps/common/scene_source.hpp '#include "view/viewer.hpp"' \
  "apps/common may include only base data sdk lines core"
expect unknown_module engine/render/frame.cpp '#include "runtime.hpp"' \
  "module 'render' is not in check_includes.sh's FLOORS"
expect pass_to_engine passes/blur/blur.cpp '#include <util/text.hpp>' \
  "an engine internal (engine/base/util/text.hpp): passes and plugins see only the SDK"
[ "$failed" = 0 ] && echo "check_includes.sh: every rule caught, the clean tree passes"
exit "$failed"
