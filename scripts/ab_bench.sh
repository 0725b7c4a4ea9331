#!/bin/bash
# A/B timing on a noisy (shared, virtualised) machine: runs two benchmark binaries AT THE SAME
# TIME, one thread each, pinned to cores 0 and 1, then again with the cores swapped, and prints
# both outputs side by side. Both see the same host load, so their difference means something
# even when sequential runs of one binary vary by +-15%.
#
# Usage: scripts/ab_bench.sh OLD_BINARY NEW_BINARY ARGS...
#   e.g. scripts/ab_bench.sh /tmp/bench_old build/release/bench/bench_examples facestyle 1 1
# (build OLD_BINARY from the earlier commit first and copy it out of the build tree).
set -euo pipefail
if [ $# -lt 2 ]; then
  echo "usage: $0 OLD_BINARY NEW_BINARY ARGS..." >&2
  exit 2
fi
old=$1
new=$2
shift 2
for b in "$old" "$new"; do
  [ -x "$b" ] || { echo "$b: not an executable" >&2; exit 2; }
done
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for round in 1 2; do
  if [ $round = 1 ]; then c_old=0; c_new=1; else c_old=1; c_new=0; fi
  taskset -c $c_old "$old" "$@" >"$out/old" 2>&1 &
  p_old=$!
  taskset -c $c_new "$new" "$@" >"$out/new" 2>&1 &
  p_new=$!
  wait $p_old
  wait $p_new
  echo "round $round (old on core $c_old, new on core $c_new)"
  sed 's/^/  old: /' "$out/old" | grep -v '^  old: *$'
  sed 's/^/  new: /' "$out/new" | grep -v '^  new: *$'
done
