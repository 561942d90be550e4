#!/bin/sh
# Every fence and query result the engine, the passes and the example plugins check goes through
# pathlet/gpu_fence.hpp, so PATHLET_SIMULATE_GPU_LATENCY reaches it: no other file calls
# glClientWaitSync or glGetSynciv or asks GL_QUERY_RESULT_AVAILABLE. engine/core/gpu_waits/ defines
# those entry points (it counts waits for the GPU and forwards each call) and checks nothing itself.
# Usage: check_fence_sites.sh SOURCE_DIR
src=${1:?usage: check_fence_sites.sh SOURCE_DIR}
hits=$(grep -rnE 'glClientWaitSync|glGetSynciv|GL_QUERY_RESULT_AVAILABLE' "$src/engine" "$src/passes" "$src/plugins" \
         --include='*.cpp' --include='*.hpp' --include='*.h' --include='*.c' |
       grep -vE '^[^:]*engine/(sdk/(src/gpu_fence\.cpp|include/pathlet/gpu_fence\.hpp)|core/gpu_waits/[^/:]*):')
if [ -n "$hits" ]; then
  echo "a fence or query checked outside pathlet/gpu_fence.hpp (use GpuFence / query_ready):"
  echo "$hits"
  exit 1
fi
echo "ok: every fence and query check goes through pathlet/gpu_fence.hpp"
