#!/bin/bash
# Adaptive splitting of a job array (`cluster submit --split-after`, cluster/split.hpp) end to end
# through the real job scripts, with a stand-in sbatch that runs each job at once (every array task
# in turn, with Slurm's variables; a job with --dependency=afterok runs only if that job's tasks
# all ended with 0). tests/CMakeLists.txt registers it. Usage: split-test.sh TILEKIT CASE
#   wang    the C=2 Wang count in 2 shards, each shard and unit stopped after a quarter of the time
#           the whole count takes here (the fastest of three, measured first; at least 3 ms): at least one round of split
#           units, then the merge: the shards' results add up to 203520 (538 orbits), every shard
#           complete (seconds). A fixed limit of a few ms was too near a unit's start-up under load:
#           units that get nothing done are split again, and the rounds grow without end.
#   corner  the C=3 corner count under t=(0,3) (about 30 CPU-s) in 2 shards, stopped after 4 s
#           each, split 2 ways: at least two rounds of split units, then 303264 (a minute; slow)
# Both: a second `cluster split` after the last round changes nothing.
set -euo pipefail
tk=$1 case=$2
case $case in
  wang) what=(--kind wang --colors 2) after=probe expect=203520 orbits_expected=538 min_rounds=1 ;;
  corner) what=(--kind corner --colors 3 --pack-arg=--impose=t=0,3:pi=1,2,0) after=4 expect=303264 orbits_expected="" min_rounds=2 ;;
  *) echo "unknown case $case" >&2; exit 2 ;;
esac
dir=$(mktemp -d /tmp/tilekit-split-test.XXXXXX)
trap 'rm -rf "$dir"' EXIT
fail() {
  echo "FAIL: $*" >&2
  for f in "$dir"/fake/jobs.log; do [ -f "$f" ] && tail -n 40 "$f" >&2; done
  exit 1
}
mkdir -p "$dir/bin" "$dir/fake"
if [ "$after" = probe ]; then  # the fastest of three counts: a slow one under a burst of load would
  whole=""                      # let a quieter shard finish within its limit, and no unit split
  for k in 1 2 3; do
    t=$("$tk" pack "${what[@]}" --mode count --threads 1 --json --db "$dir/probe$k.sqlite" 2>/dev/null |
      grep -o '"seconds":[0-9.eE+-]*' | head -n 1 | cut -d: -f2)
    [ -n "$t" ] || fail "the probe count printed no seconds"
    whole=$(awk -v a="$t" -v b="${whole:-$t}" 'BEGIN { print (a < b ? a : b) }')
  done
  after=$(awk -v t="$whole" 'BEGIN { a = t / 4; if (a < 0.003) a = 0.003; printf "%.4f", a }')
fi
export FAKE_SLURM=$dir/fake
cat >"$dir/bin/sbatch" <<'EOF'
#!/bin/bash
# sbatch --parsable [--array=A-B] [--dependency=afterok:ID] SCRIPT ARGS...: runs it now.
set -u
id=$(cat "$FAKE_SLURM/next" 2>/dev/null || echo 100)
echo $((id + 1)) >"$FAKE_SLURM/next"
lo="" hi="" after=""
while [[ $1 == --* ]]; do
  case $1 in
    --array=*) r=${1#--array=}; lo=${r%-*}; hi=${r#*-} ;;
    --dependency=afterok:*) after=${1#--dependency=afterok:} ;;
  esac
  shift
done
script=$1
shift
if [ -z "$lo" ] && grep -q '^#SBATCH --array=' "$script"; then
  r=$(sed -n 's/^#SBATCH --array=\([0-9]*-[0-9]*\).*/\1/p' "$script")
  lo=${r%-*} hi=${r#*-}
fi
echo "job $id: $script ${lo:+array $lo-$hi} ${after:+after $after} $*" >>"$FAKE_SLURM/jobs.log"
if [ -n "$after" ] && [ -e "$FAKE_SLURM/failed-$after" ]; then
  echo "job $id: never runs (job $after failed)" >>"$FAKE_SLURM/jobs.log"
elif [ -n "$lo" ]; then
  for ((t = lo; t <= hi; t++)); do
    SLURM_JOB_ID=$id$t SLURM_ARRAY_JOB_ID=$id SLURM_ARRAY_TASK_ID=$t SLURM_CPUS_PER_TASK=1 \
      bash "$script" "$@" >>"$FAKE_SLURM/jobs.log" 2>&1 || touch "$FAKE_SLURM/failed-$id"
  done
else
  SLURM_JOB_ID=$id bash "$script" "$@" >>"$FAKE_SLURM/jobs.log" 2>&1 || touch "$FAKE_SLURM/failed-$id"
fi
echo "$id"
EOF
chmod +x "$dir/bin/sbatch"
export PATH="$dir/bin:$PATH"

run=$dir/run
"$tk" cluster submit "${what[@]}" --mode count --shards 2 --split-after "$after" --split-ways 2 \
  --tilekit "$tk" --sbatch "$dir/bin/sbatch" --run-dir "$run" --json >"$dir/submit.json" ||
  fail "cluster submit failed: $(cat "$dir/submit.json")"
ls "$dir"/fake/failed-* >/dev/null 2>&1 && fail "a job failed: $(ls "$dir"/fake/failed-*)"
[ -s "$run/units/round-1.tsv" ] || fail "no round 1: no shard ran past its $after s"
((min_rounds < 2)) || [ -s "$run/units/round-2.tsv" ] || fail "no round 2: every unit of round 1 finished within $after s"
for i in 0 1; do
  grep -q '"complete":true' "$run/shards/shard-$i.done.json" || fail "shard $i not complete"
done
sum=$(grep -ho '"solutions":[0-9]*' "$run"/shards/shard-{0,1}.done.json | cut -d: -f2 | paste -sd+ | bc)
orbits=$(grep -ho '"orbits":[0-9]*' "$run"/shards/shard-{0,1}.done.json | cut -d: -f2 | paste -sd+ | bc)
[ "$sum" = "$expect" ] || fail "the shards' results add up to $sum, not $expect"
[ -z "$orbits_expected" ] || [ "$orbits" = "$orbits_expected" ] || fail "orbits $orbits, not $orbits_expected"
grep -q "the shards reported $expect solutions in all" "$dir/fake/jobs.log" || fail "the merge job did not merge"
rounds=$(ls "$run"/units/round-*.tsv | wc -l)
units=$(cat "$run"/units/round-*.tsv | wc -l)
# The last round's state split again: nothing left, nothing changes.
before=$(cat "$run"/shards/shard-*.done.json | md5sum)
last=$rounds
out=$("$tk" cluster split --run-dir "$run" --after-round "$last" --json)
grep -q '"units":0' <<<"$out" || fail "after the last round: $out"
[ "$(cat "$run"/shards/shard-*.done.json | md5sum)" = "$before" ] || fail "splitting again changed a result"
"$tk" cluster status --run-dir "$run" --json | grep -q '"done":2' || fail "cluster status does not show 2 done shards"
echo "ok: $expect through $rounds rounds of $units split units and the merge"
