#!/usr/bin/env bash
# Runs the libFuzzer targets of a build configured with -DVOXGI_FUZZ=ON (docs/inputs.md), each
# for SECONDS, starting from a fresh copy of its seeds, and fails on any crash, sanitizer report,
# timeout or out-of-memory. Prints per target the executions and executions per second.
#
#   tests/fuzz/run-libfuzzer.sh BUILD_DIR SECONDS [TARGET...]
#
# TARGET: json graph expression bench gltf (default: all). Each run gets a folder
# BUILD_DIR/fuzz/run-<time>-<pid>/ with corpus/<target>/ (seeds plus what the run found new),
# artifacts/ (inputs that failed) and <target>.log. Environment: VOXGI_FUZZ_TIMEOUT (seconds per
# input, default 20), VOXGI_FUZZ_RSS_MB (default 2048; at least 4096 for glTF seeded with files
# over 1 MiB, as libFuzzer keeps its corpus in memory), VOXGI_FUZZ_SCENES (more glTF seeds,
# default ../shared/scenes; empty: none), VOXGI_FUZZ_ARGS (more libFuzzer flags, e.g.
# "-jobs=4 -workers=4"), VOXGI_FUZZ_PARALLEL (targets run at once, default one per core),
# ASAN_OPTIONS (default detect_leaks=0, as in tests/run.sh).
set -euo pipefail
if [ "$#" -lt 2 ]; then
  echo "usage: $0 BUILD_DIR SECONDS [json|graph|expression|bench|gltf ...]" >&2
  exit 2
fi
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="$(cd "$1" && pwd)"
seconds="$2"
shift 2
targets=("$@")
[ "${#targets[@]}" -gt 0 ] || targets=(json graph expression bench gltf)
here="$repo/tests/fuzz/libfuzzer"
timeout_s="${VOXGI_FUZZ_TIMEOUT:-20}"
rss_mb="${VOXGI_FUZZ_RSS_MB:-2048}"
scenes="${VOXGI_FUZZ_SCENES-$repo/../shared/scenes}"
parallel="${VOXGI_FUZZ_PARALLEL:-$(nproc)}"
if ! [[ "$parallel" =~ ^[1-9][0-9]*$ ]]; then
  echo "VOXGI_FUZZ_PARALLEL='$parallel': expected a whole number of targets at once, at least 1" >&2
  exit 2
fi

run="$build/fuzz/run-$(date +%Y%m%d-%H%M%S)-$$"
mkdir -p "$run/artifacts"
scratch_base=/dev/shm
[ -d "$scratch_base" ] && [ -w "$scratch_base" ] || scratch_base="${TMPDIR:-/tmp}"
scratch="$(mktemp -d "$scratch_base/voxgi-fuzz.XXXXXX")"
trap 'rm -rf "$scratch"' EXIT
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=0}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1}"
export VOXGI_FUZZ_SCRATCH="$scratch"

# Seeds of each target into corpus/<target>; prints the -max_len it gets (the largest seed, at
# least 64 KiB: graph, bench and glTF files of a few KiB leave room to grow).
seed() {
  local target="$1" corpus="$run/corpus/$1"
  mkdir -p "$corpus"
  case "$target" in
    json | graph)
      find "$repo/graphs" -name '*.json' -exec cp {} "$corpus/" \;
      cp "$repo/docs/bench-report/bench.json" "$corpus/bench-report.json"
      ;;
    expression) cp "$here/seeds/expression/"* "$corpus/" ;;
    bench)
      cp "$repo/graphs/bench.json" "$corpus/bench.json"
      cp "$repo/docs/bench-report/bench.json" "$corpus/bench-report.json"
      ;;
    gltf)
      if [ -n "$scenes" ] && [ -d "$scenes" ]; then
        "$build/bin/voxgi_fuzz_gltf_seeds" "$corpus" "$scenes"
      else
        echo "fuzz gltf: ${scenes:-VOXGI_FUZZ_SCENES is empty}${scenes:+ not found}; seeding" \
          "with the generated documents only" >&2
        "$build/bin/voxgi_fuzz_gltf_seeds" "$corpus"
      fi
      ;;
    *)
      echo "unknown fuzz target '$target' (json graph expression bench gltf)" >&2
      exit 2
      ;;
  esac
  chmod -R u+w "$corpus"
  local largest
  largest="$(find "$corpus" -type f -printf '%s\n' | sort -n | tail -1)"
  [ "$target" = expression ] && echo 16384 && return
  echo $((largest > 65536 ? largest : 65536))
}

# A libFuzzer final statistic from a log, "?" when the log has none.
stat_of() {
  local value
  value="$(sed -n "s/^stat::$1: *//p" "$2" | tail -1)"
  echo "${value:-?}"
}

# One target's run: its log in $run/<target>.log, its summary line in $run/<target>.result
# (ending in FAILED and the exit status when it failed).
fuzz_one() {
  local target="$1" binary="$build/bin/voxgi_fuzz_$1"
  local max_len dict log rss rc=0 result=ok artifacts
  max_len="$(seed "$target")"
  dict="$here/inputs.dict"
  [ "$target" = expression ] && dict="$here/expression.dict"
  log="$run/$target.log"
  rss="$rss_mb"
  [ "$max_len" -gt 1048576 ] && [ "$rss" -lt 4096 ] && rss=4096
  echo "fuzz $target: ${seconds}s, max_len $max_len, corpus $run/corpus/$target"
  # shellcheck disable=SC2086  # VOXGI_FUZZ_ARGS is a list of flags
  (cd "$run" && "$binary" -max_total_time="$seconds" -timeout="$timeout_s" \
    -rss_limit_mb="$rss" -max_len="$max_len" -dict="$dict" -print_final_stats=1 \
    -artifact_prefix="$run/artifacts/$target-" ${VOXGI_FUZZ_ARGS:-} "$run/corpus/$target") \
    >"$log" 2>&1 || rc=$?
  artifacts=("$run/artifacts/$target-"*)
  [ -e "${artifacts[0]}" ] || artifacts=()
  if [ "$rc" -ne 0 ] || [ "${#artifacts[@]}" -gt 0 ] ||
    grep -qE '^(==[0-9]+==ERROR|SUMMARY: |.*runtime error: )' "$log"; then
    result="FAILED (exit $rc)"
  fi
  printf '%-10s %6ss %12s execs %8s exec/s %6s new %6s MB  %s\n' "$target" "$seconds" \
    "$(stat_of number_of_executed_units "$log")" "$(stat_of average_exec_per_sec "$log")" \
    "$(stat_of new_units_added "$log")" "$(stat_of peak_rss_mb "$log")" "$result" \
    >"$run/$target.result"
}

for target in "${targets[@]}"; do
  if [ ! -x "$build/bin/voxgi_fuzz_$target" ]; then
    echo "$build/bin/voxgi_fuzz_$target is missing: configure $build with -DVOXGI_FUZZ=ON and" \
      "build voxgi_fuzz_targets" >&2
    exit 2
  fi
done
# Each libFuzzer process uses one core: the targets run side by side, one per core
# (VOXGI_FUZZ_PARALLEL), each for its full SECONDS.
for target in "${targets[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$parallel" ]; do wait -n || true; done
  fuzz_one "$target" &
done
wait

failed=()
summary=()
for target in "${targets[@]}"; do
  line="$(cat "$run/$target.result" 2>/dev/null || echo "$target: no result (the run stopped)")"
  summary+=("$line")
  case "$line" in
    *FAILED* | *"no result"*)
      failed+=("$target")
      echo "fuzz $target failed; last lines of $run/$target.log:" >&2
      tail -n 40 "$run/$target.log" >&2 || true
      for a in "$run/artifacts/$target-"*; do
        if [ -e "$a" ]; then echo "fuzz $target: failing input $a" >&2; fi
      done
      ;;
  esac
done

echo "libFuzzer runs ($run):"
printf '  %s\n' "${summary[@]}"
if [ "${#failed[@]}" -gt 0 ]; then
  echo "fuzzing failed: ${failed[*]} (inputs in $run/artifacts, logs in $run)" >&2
  exit 1
fi
