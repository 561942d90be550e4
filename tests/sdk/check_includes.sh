#!/usr/bin/env bash
# Who may include whom (ARCHITECTURE.md's module table), checked on the sources before anyone
# builds. Prints every violation with file and line and exits 1.
#   tests/sdk/check_includes.sh [SOURCE_DIR]
#
# 1. A pass or plugin (passes/<name>/, plugins/<name>/, their own sources, not their tests/)
#    includes only files of its own folder, the SDK (<pathlet/...>), shared GLSL (shaders/,
#    engine/lines/shaders/) from its shaders, and system and third-party headers.
# 2. The engine's floors: every C++ file under engine/ (tests excepted) includes only its own
#    module and the modules FLOORS lists for it, so no include runs up a floor, and only the
#    `pathlet` command (apps/cli) includes apps/cli. CMake's PRIVATE include folders make some of
#    these mistakes compile errors; this names every one, with the rule.
set -u
SRC=${1:-$(cd "$(dirname "$0")/../.." && pwd)}
cd "$SRC" || exit 2
bad=0
report() { echo "$1:$2: $3"; bad=1; }
include_re='^[[:space:]]*#[[:space:]]*include[[:space:]]*(["<])([^">]+)[">]'
# The SDK's headers (installed together as include/pathlet/).
SDK_INCLUDE_DIRS="engine/base/include engine/sdk/include engine/lines/include"
in_sdk() { local d; for d in $SDK_INCLUDE_DIRS; do [ -f "$d/$1" ] && return 0; done; return 1; }

# ---- 1. passes and plugins: their own folder and the SDK ---------------------------------
for f in passes/*/*.cpp passes/*/*.hpp plugins/*/*.cpp plugins/*/*.hpp \
         passes/*/*.frag passes/*/*.vert passes/*/*.geom passes/*/*.comp passes/*/*.glsl \
         plugins/*/*.frag plugins/*/*.vert plugins/*/*.geom plugins/*/*.comp plugins/*/*.glsl; do
  [ -f "$f" ] || continue
  dir=$(dirname "$f")
  case "$f" in *.cpp|*.hpp) kind=cxx ;; *) kind=glsl ;; esac
  n=0
  while IFS= read -r line; do
    n=$((n + 1))
    [[ "$line" =~ $include_re ]] || continue
    delim=${BASH_REMATCH[1]} inc=${BASH_REMATCH[2]}
    if [ "$delim" = '"' ]; then
      [ -f "$dir/$inc" ] && continue
      if [ "$kind" = glsl ] && { [ -f "shaders/$inc" ] || [ -f "engine/lines/shaders/$inc" ]; }; then continue; fi
      report "$f" "$n" "includes \"$inc\", which is neither in its folder nor in the SDK: what a pass needs belongs in the SDK (engine/sdk)"
    else
      case "$inc" in
        pathlet/*)
          in_sdk "$inc" ||
            report "$f" "$n" "includes <$inc>, which the SDK does not have (engine/base/include, engine/sdk/include, engine/lines/include)" ;;
        *)
          for root in engine/core engine/data engine/base engine/apps engine/apps/cli; do
            [ -f "$root/$inc" ] && { report "$f" "$n" "includes <$inc>, an engine internal ($root/$inc): passes and plugins see only the SDK"; break; }
          done ;;
      esac
    fi
  done <"$f"
done

# ---- 2. the engine's floors ---------------------------------------------------------------
# A module is a folder under engine/ (apps/ is one room per program). Each may include itself
# and the modules listed here; a lower floor never includes a higher one.
declare -A FLOORS=(
  [base]=""                                        # the ground floor: std, GLM, JSON only
  [data]="base"
  [sdk]="base"                                     # installed: nothing of the engine's internals
  [lines]="base sdk"
  [core]="base data sdk lines"
  [apps/common]="base data sdk lines core"         # what every front end shares (scene loading)
  [apps/bench]="base data sdk lines core apps/common"
  [apps/quality]="base data sdk lines core apps/common"
  [apps/view]="base data sdk lines core apps/common"
  [apps/python]="base data sdk lines core apps/common apps/bench apps/quality"
  [apps/cli]="base data sdk lines core apps/common apps/bench apps/quality apps/view"
)
# Where the compiler finds a quoted include that is not beside the file, and an angled one: the
# include folders the targets give (engine/CMakeLists.txt, engine/apps/CMakeLists.txt).
ROOTS="engine/base/include engine/base engine/sdk/include engine/lines/include engine/core engine/data
       engine/apps engine/apps/quality engine/apps/cli"
module_of() {  # sets MODULE: engine/apps/cli/x.cpp -> apps/cli, engine/core/graph/y.hpp -> core
  local rest=${1#engine/}
  MODULE=""
  case "$rest" in
    apps/*/*) rest=${rest#apps/}; MODULE="apps/${rest%%/*}" ;;
    */*) MODULE=${rest%%/*} ;;
  esac
}
# One grep for every include line of the engine's C++ (tests excepted): FILE:LINE:TEXT.
while IFS= read -r hit; do
  f=${hit%%:*} rest=${hit#*:}
  n=${rest%%:*} line=${rest#*:}
  [[ "$line" =~ $include_re ]] || continue
  delim=${BASH_REMATCH[1]} inc=${BASH_REMATCH[2]}
  module_of "$f"
  from=$MODULE
  [ -n "$from" ] || continue
  if [ -z "${FLOORS[$from]+set}" ]; then
    report "$f" "$n" "module '$from' is not in check_includes.sh's FLOORS: say which modules it may include"
    continue
  fi
  [ "$delim" = '"' ] && [ -f "${f%/*}/$inc" ] && continue
  target=""
  for root in $ROOTS; do
    [ -f "$root/$inc" ] && { target="$root/$inc"; break; }
  done
  [ -n "$target" ] || continue  # system, third-party or generated
  module_of "$target"
  to=$MODULE
  [ "$to" = "$from" ] && continue
  case " ${FLOORS[$from]} " in *" $to "*) continue ;; esac
  if [ "$to" = apps/cli ]; then
    report "$f" "$n" "includes $target: only the pathlet command (engine/apps/cli) includes cli/; what other programs share goes in engine/apps/common"
  else
    report "$f" "$n" "includes $target: $from may include only ${FLOORS[$from]:-std, GLM and JSON} (no include runs up a floor; ARCHITECTURE.md)"
  fi
done < <(find engine \( -name tests -prune \) -o -type f \( -name '*.cpp' -o -name '*.hpp' \) -print0 | sort -z |
         xargs -0 grep -nE '^[[:space:]]*#[[:space:]]*include' /dev/null)

[ "$bad" -eq 0 ] && echo "check_includes: every pass and plugin includes only its own folder and the SDK; every engine module only the floors below it; only cli/ includes cli/"
exit "$bad"
