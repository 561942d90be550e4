#!/usr/bin/env bash
# Compiler launcher (cmake/PathletBuild.cmake, RULE_LAUNCH_COMPILE): runs one compile and appends a
# line to LOG: user and system CPU seconds, wall seconds, the object file (a ccache hit shows
# as a few hundredths). scripts/build-times.sh sums it per target and lists the slowest units.
#   cmake/unit_time.sh LOG COMPILER ARGS...
log=$1
shift
obj="" prev=""
for a in "$@"; do
  [ "$prev" = -o ] && obj=$a
  prev=$a
done
start=${EPOCHREALTIME/./}
"$@"
rc=$?
end=${EPOCHREALTIME/./}
# This shell's children's CPU time in clock ticks (USER_HZ, 100 on Linux): fields 16 and 17 of
# /proc/PID/stat.
read -r -a stat </proc/$$/stat
tick=100
wall=$(((end - start) / 10000))
printf '%d.%02d\t%d.%02d\t%d.%02d\t%s\n' $((stat[15] / tick)) $((stat[15] % tick)) $((stat[16] / tick)) \
  $((stat[16] % tick)) $((wall / 100)) $((wall % 100)) "$([ "${obj:0:1}" = / ] || printf '%s/' "$PWD")$obj" >>"$log"
exit $rc
