#!/usr/bin/env bash
# Used by foam-solvers/CMakeLists.txt: build one solver/utility folder with wmake, in the build
# tree so wmake's Make/linux64GccDPInt32Opt object folders never land in the source tree.
#
#   wmake-in-build-tree.sh ENV_FILE SOURCE_DIR WORK_DIR LOG_FILE
#
# Copies SOURCE_DIR into WORK_DIR keeping timestamps (so wmake recompiles only what changed;
# files no longer in SOURCE_DIR are removed from WORK_DIR), runs wmake there through ENV_FILE
# and keeps its output in LOG_FILE; on failure prints the tail of the log.
set -euo pipefail
env_file=$1 src=$2 work=$3 log=$4

mkdir -p "$work" "$(dirname "$log")"
cp -a "$src/." "$work/"
# A file since removed from the source folder goes from the copy too (wmake's own output
# aside): a header left there would be included before the shared one of the same name. wmake's
# object folder goes with it, since its dependency files may name the removed file (make then
# stops with "No rule to make target"): that folder is rebuilt from scratch.
removed=0
while IFS= read -r -d '' file; do
  if [ ! -e "$src/$file" ]; then
    rm -f "$work/$file"
    removed=1
  fi
done < <(cd "$work" && find . -type f ! -path './Make/linux64*' ! -path './lnInclude/*' -print0)
if [ "$removed" = 1 ]; then
  rm -rf "$work"/Make/linux64*
fi
if ! (cd "$work" && bash "$env_file" wmake) >"$log" 2>&1; then
  tail -n 40 "$log" >&2
  echo "wmake failed in $work (source $src); full log: $log" >&2
  exit 1
fi
