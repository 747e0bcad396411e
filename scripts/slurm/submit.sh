#!/usr/bin/env bash
# Submits a FlowScape release to Slurm: a job array of N shards (gen_flowscape --shard K/N) into one
# shared folder, and a merge job that runs when all of them succeeded.
#
#   scripts/slurm/submit.sh --shards 16 --out /scratch/flowscape [--bin build/apps] [--logs DIR]
#       [--only 3,7] [--cpus 8] [--sbatch "--partition=cpu --time=04:00:00"] -- [gen_flowscape options]
#
# Job logs go to --logs (default: <out>-slurm-logs, beside the release, not in it).
#
# Resubmitting the same command resumes: finished frames are skipped. --only resubmits some array
# tasks (e.g. the ones that failed) and the merge after them.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
shards="" out="" bin="$here/../../build/apps" only="" cpus=2 extra="" logs=""
while (($#)); do
  case $1 in
    --shards) shards=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --bin) bin=$2; shift 2 ;;
    --only) only=$2; shift 2 ;;
    --cpus) cpus=$2; shift 2 ;;
    --logs) logs=$2; shift 2 ;;
    --sbatch) extra=$2; shift 2 ;;
    --) shift; break ;;
    *) echo "submit.sh: unknown option $1 (see the comment at the top)" >&2; exit 2 ;;
  esac
done
[[ $shards =~ ^[1-9][0-9]*$ ]] || { echo "submit.sh: --shards N (N >= 1) is required" >&2; exit 2; }
[[ -n $out ]] || { echo "submit.sh: --out DIR is required" >&2; exit 2; }
bin=$(cd "$bin" && pwd) || { echo "submit.sh: no such folder $bin" >&2; exit 2; }
[[ -x $bin/gen_flowscape ]] || { echo "submit.sh: $bin/gen_flowscape not found (build first)" >&2; exit 2; }
# a typo in the options fails here, not in N array tasks (checked against an empty folder: what
# killed tasks left in $out is for their reruns to clean, not a reason to refuse)
blank=$(mktemp -d)
"$bin/gen_flowscape" "$@" --out "$blank/release" --shard "0/$shards" --check >/dev/null ||
  { rmdir "$blank"; exit 2; }
rmdir "$blank"
mkdir -p "$out" "${logs:=$out-slurm-logs}"
out=$(cd "$out" && pwd) logs=$(cd "$logs" && pwd)
array=${only:-0-$((shards - 1))}
export FLOWSCAPE_OUT=$out FLOWSCAPE_SHARDS=$shards FLOWSCAPE_BIN=$bin FLOWSCAPE_ARGS="$*"
read -r -a sbatch_extra <<<"$extra"
shard_job=$(sbatch --parsable --export=ALL --array="$array" --cpus-per-task="$cpus" \
  --chdir="$logs" --output="$logs/flowscape-%A_%a.out" "${sbatch_extra[@]}" \
  "$here/flowscape_shard.sbatch")
merge_job=$(sbatch --parsable --export=ALL --dependency="afterok:${shard_job%%;*}" \
  --chdir="$logs" --output="$logs/flowscape-merge-%j.out" "${sbatch_extra[@]}" \
  "$here/flowscape_merge.sbatch")
echo "shards: job ${shard_job%%;*} (array $array), merge: job ${merge_job%%;*}, release: $out, logs: $logs"
