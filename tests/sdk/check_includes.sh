#!/usr/bin/env bash
# The SDK is the only boundary: a pass or plugin (passes/<name>/, plugins/<name>/, their own
# sources, not their tests/) includes only
#   - files of its own folder ("x.hpp", "x.glsl"),
#   - the SDK (<pathlet/...> from engine/sdk/include or engine/lines/include),
#   - shared GLSL (shaders/, engine/lines/shaders/) from its shaders,
#   - system and third-party headers (<glm/...>, <vector>, ...), never engine internals.
# Prints every violation with file and line and exits 1; CMake's PRIVATE include folders make
# the same mistake a compile error, this names it before anyone builds.
#   tests/sdk/check_includes.sh [SOURCE_DIR]
set -u
SRC=${1:-$(cd "$(dirname "$0")/../.." && pwd)}
cd "$SRC" || exit 2
bad=0
report() { echo "$1:$2: $3"; bad=1; }
for f in passes/*/*.cpp passes/*/*.hpp plugins/*/*.cpp plugins/*/*.hpp \
         passes/*/*.frag passes/*/*.vert passes/*/*.geom passes/*/*.comp passes/*/*.glsl \
         plugins/*/*.frag plugins/*/*.vert plugins/*/*.geom plugins/*/*.comp plugins/*/*.glsl; do
  [ -f "$f" ] || continue
  dir=$(dirname "$f")
  case "$f" in *.cpp|*.hpp) kind=cxx ;; *) kind=glsl ;; esac
  n=0
  re='^[[:space:]]*#[[:space:]]*include[[:space:]]*(["<])([^">]+)[">]'
  while IFS= read -r line; do
    n=$((n + 1))
    [[ "$line" =~ $re ]] || continue
    delim=${BASH_REMATCH[1]} inc=${BASH_REMATCH[2]}
    if [ "$delim" = '"' ]; then
      [ -f "$dir/$inc" ] && continue
      if [ "$kind" = glsl ] && { [ -f "shaders/$inc" ] || [ -f "engine/lines/shaders/$inc" ]; }; then continue; fi
      report "$f" "$n" "includes \"$inc\", which is neither in its folder nor in the SDK: what a pass needs belongs in the SDK (engine/sdk)"
    else
      case "$inc" in
        pathlet/*)
          [ -f "engine/sdk/include/$inc" ] || [ -f "engine/lines/include/$inc" ] ||
            report "$f" "$n" "includes <$inc>, which the SDK does not have (engine/sdk/include/pathlet, engine/lines/include/pathlet)" ;;
        *)
          for root in engine/core engine/data engine/apps engine/apps/cli; do
            [ -f "$root/$inc" ] && { report "$f" "$n" "includes <$inc>, an engine internal ($root/$inc): passes and plugins see only the SDK"; break; }
          done ;;
      esac
    fi
  done <"$f"
done
# The SDK's own code (engine/sdk/src, engine/lines/src) likewise: its folder, the SDK, system
# headers; never engine/core or engine/data (the SDK is installed without them).
for f in engine/sdk/src/*.cpp engine/sdk/src/*.hpp engine/lines/src/*.cpp engine/lines/src/*.hpp; do
  [ -f "$f" ] || continue
  dir=$(dirname "$f")
  n=0
  re='^[[:space:]]*#[[:space:]]*include[[:space:]]*(["<])([^">]+)[">]'
  while IFS= read -r line; do
    n=$((n + 1))
    [[ "$line" =~ $re ]] || continue
    inc=${BASH_REMATCH[2]}
    [ -f "$dir/$inc" ] && continue
    case "$inc" in
      pathlet/*) [ -f "engine/sdk/include/$inc" ] || [ -f "engine/lines/include/$inc" ] ||
                   report "$f" "$n" "includes <$inc>, which the SDK does not have" ;;
      *) for root in engine/core engine/data engine/apps; do
           [ -f "$root/$inc" ] && { report "$f" "$n" "the SDK includes $root/$inc, an engine internal: the SDK is installed without it"; break; }
         done ;;
    esac
  done <"$f"
done
# The ground floor: the SDK's CPU-only headers every layer builds on (text.hpp,
# scene.hpp) and the engine's file and text utilities (engine/data/util) include only system and
# third-party headers, nothing of a layer above them.
for f in engine/sdk/include/pathlet/text.hpp engine/sdk/include/pathlet/scene.hpp engine/data/util/*.hpp; do
  [ -f "$f" ] || continue
  n=0
  re='^[[:space:]]*#[[:space:]]*include[[:space:]]*(["<])([^">]+)[">]'
  while IFS= read -r line; do
    n=$((n + 1))
    [[ "$line" =~ $re ]] || continue
    delim=${BASH_REMATCH[1]} inc=${BASH_REMATCH[2]}
    case "$delim$inc" in
      '<'pathlet/*|'"'*) report "$f" "$n" "includes $inc: the ground floor (std, GLM, JSON only) reaches up into no layer" ;;
    esac
  done <"$f"
done
[ "$bad" -eq 0 ] && echo "check_includes: every pass and plugin includes only its own folder and the SDK; so does the SDK; the ground floor includes no layer above it"
exit "$bad"
