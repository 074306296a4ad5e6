#!/usr/bin/env bash
# The atlas on Slurm (ctest label slurm): starts a one-node cluster on this
# machine (scripts/atlas-slurm/local-cluster: its own munged, slurmctld and
# slurmd, every file under a temporary directory), submits a four-shard
# atlas array and the merge as a dependent job (scripts/atlas-slurm/submit),
# waits, and checks that the merged points.csv is byte for byte the
# unsharded run's. Every daemon it started is killed by pid on exit, failed
# or not. Needs root, slurm-wlm and munge: without them it is skipped
# (exit 77).
#
#   slurm_atlas.sh CONTACT2D SOURCE_DIR
set -euo pipefail
exe="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"
root="$2"
spec="$root/tests/slurm/tiny.toml"
if [ "$(id -u)" -ne 0 ]; then echo "skipped: needs root"; exit 77; fi
for tool in munged slurmctld slurmd sbatch squeue sinfo; do
  command -v "$tool" >/dev/null || { echo "skipped: $tool not found (Debian: slurm-wlm munge)"; exit 77; }
done

tmp="$(mktemp -d "${TMPDIR:-/tmp}/contact2d-slurm.XXXXXX")"
cluster="$tmp/cluster"
cleanup() {
  local status=$?
  "$root/scripts/atlas-slurm/local-cluster" stop "$cluster" || true
  if [ $status -ne 0 ]; then
    echo "--- failed; the cluster's and the jobs' logs:"
    tail -n 20 "$cluster"/*.log "$tmp"/out/logs/* 2>/dev/null || true
  fi
  rm -rf "$tmp"
  exit $status
}
trap cleanup EXIT
trap 'exit 130' INT TERM HUP
start=$SECONDS

"$root/scripts/atlas-slurm/local-cluster" start "$cluster" >/dev/null
export SLURM_CONF="$cluster/slurm.conf"
echo "cluster up after $((SECONDS - start)) s"

ids="$("$root/scripts/atlas-slurm/submit" "$spec" "$tmp/out" 4 "$exe")"
read -r array merge <<<"$ids"
echo "submitted array $array and merge $merge"
# The merge job leaves the queue when it is done (or cancelled: its
# dependency failed).
for _ in $(seq 240); do
  squeue -h -j "$array,$merge" 2>/dev/null | grep -q . || break
  sleep 0.25
done
if squeue -h -j "$array,$merge" 2>/dev/null | grep -q .; then
  echo "FAIL: the jobs are still queued after 60 s"; squeue; exit 1
fi
echo "array and merge done after $((SECONDS - start)) s"
for i in 1 2 3 4; do
  [ -f "$tmp/out/shard-$i-of-4/points.csv" ] || { echo "FAIL: shard $i/4 wrote no points.csv"; exit 1; }
done
[ -f "$tmp/out/merged/points.csv" ] || { echo "FAIL: the merge wrote no points.csv"; exit 1; }
[ -f "$tmp/out/merged/summary.md" ] || { echo "FAIL: the merge wrote no summary.md"; exit 1; }

"$exe" atlas "$spec" --out "$tmp/whole" --threads 2 --quiet
if ! cmp "$tmp/out/merged/points.csv" "$tmp/whole/points.csv"; then
  echo "FAIL: the merged shards differ from the unsharded run"
  diff "$tmp/out/merged/points.csv" "$tmp/whole/points.csv" | head -20
  exit 1
fi
rows=$(($(wc -l <"$tmp/whole/points.csv") - 1))
echo "PASS: 4 Slurm shards merged equal the unsharded run ($rows points), $((SECONDS - start)) s in all"
