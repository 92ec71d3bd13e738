#!/usr/bin/env bash
# Used by foam-solvers/CMakeLists.txt: build one solver/utility folder with wmake, in the build
# tree so wmake's Make/linux64GccDPInt32Opt object folders never land in the source tree.
#
#   wmake-in-build-tree.sh ENV_FILE SOURCE_DIR WORK_DIR LOG_FILE
#
# Copies SOURCE_DIR into WORK_DIR keeping timestamps (so wmake recompiles only what changed),
# runs wmake there through ENV_FILE and keeps its output in LOG_FILE; on failure prints the
# tail of the log.
set -euo pipefail
env_file=$1 src=$2 work=$3 log=$4

mkdir -p "$work" "$(dirname "$log")"
cp -a "$src/." "$work/"
if ! (cd "$work" && bash "$env_file" wmake) >"$log" 2>&1; then
  tail -n 40 "$log" >&2
  echo "wmake failed in $work (source $src); full log: $log" >&2
  exit 1
fi
