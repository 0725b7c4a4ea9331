#!/usr/bin/env bash
# Side by side with ebsynth (issue 15): ebsynth's public-domain CPU build, compiled here from
# ../shared/anchors/ebsynth with the line of its build-linux-cpu_only.sh (into build/, never
# copied into the project), and `exemplar stylize` on the same inputs and guide weights (the
# ebsynth authors' weights, ../shared/data/SOURCES.md), one after the other with the same thread
# count. Prints per example and tool: wall time, peak RSS (/usr/bin/time), texture kept and
# patch fidelity (bench_examples --measure), and the ratios against ebsynth. Outputs stay in
# build/vs_ebsynth/ to look at.
#
# Usage: bash bench/vs_ebsynth.sh [threads] [extra exemplar flags...]
#   bash bench/vs_ebsynth.sh 2                    # default quality
#   bash bench/vs_ebsynth.sh 2 --quality best     # compare a preset (or any stylize flags)
set -euo pipefail
cd "$(dirname "$0")/.."
threads=${1:-2}
shift || true
extra=("$@")  # extra exemplar flags
anchor=../shared/anchors/ebsynth
data=../shared/data/guided/ebsynth
if [[ ! -f $anchor/src/ebsynth.cpp || ! -d $data ]]; then
  echo "vs_ebsynth: $anchor or $data is absent (optional benchmark data); nothing compared"
  exit 0
fi
if [[ ! -x /usr/bin/time ]]; then
  echo "vs_ebsynth: /usr/bin/time is missing (Debian package 'time')" >&2
  exit 1
fi

# ebsynth, rebuilt when its sources are newer than the binary (about a minute).
eb=build/ebsynth-anchor/ebsynth
if [[ ! -x $eb || $anchor/src/ebsynth_cpu.cpp -nt $eb ]]; then
  mkdir -p build/ebsynth-anchor
  echo "vs_ebsynth: building ebsynth (CPU) from $anchor" >&2
  g++ $anchor/src/ebsynth.cpp $anchor/src/ebsynth_cpu.cpp $anchor/src/ebsynth_nocuda.cpp \
    -DNDEBUG -O3 -fopenmp -I"$anchor/include" -std=c++11 -o $eb
fi
bash scripts/build.sh exemplar bench_examples > /dev/null
ex=build/release/exemplar
measure=build/release/bench/bench_examples
out=build/vs_ebsynth
mkdir -p $out

# Guides per example: source target weight, ...
declare -A style guides
style[stylit]=$data/stylit/source_style.png
guides[stylit]="fullgi 0.5 dirdif 0.5 dirspc 0.5 indirb 0.5"
style[facestyle]=$data/facestyle/source_painting.png
guides[facestyle]="Gapp 0.5 Gseg 1.5 Gpos 10"
style[texbynum]=$data/texbynum/source_photo.png
guides[texbynum]="segment 1"
# Guided texture synthesis (EmbarkStudios/texture-synthesis imgs/2.jpg): masks as the guide.
style[guided2]=$data/../texture-synthesis/2.jpg
guides[guided2]="mask 1"

# Runs "$@" under /usr/bin/time; sets secs and mib.
timed() {
  local log=$out/time.txt
  /usr/bin/time -f "%e %M" -o $log "$@" > /dev/null 2>> $out/stderr.txt
  read -r secs kb < $log
  mib=$(awk -v k="$kb" 'BEGIN { printf "%.0f", k / 1024 }')
}

printf "%-10s %-9s %8s %8s %9s %8s %9s\n" example tool "time s" "x eb" "RSS MiB" texture fidelity
for name in stylit facestyle texbynum guided2; do
  eb_args=() ex_args=()
  set -- ${guides[$name]}
  while (($# > 0)); do
    if [[ $name == guided2 ]]; then
      s=$data/../texture-synthesis/masks/2_example.jpg t=$data/../texture-synthesis/masks/2_target.jpg
    else
      s=$data/$name/source_$1.png t=$data/$name/target_$1.png
    fi
    eb_args+=(-guide "$s" "$t" -weight "$2")
    ex_args+=(--guide "$s" "$t" --weight "$2")
    shift 2
  done
  declare -A secs_of
  for tool in ebsynth exemplar; do
    file=$out/${name}_$tool.png
    if [[ $tool == ebsynth ]]; then
      OMP_NUM_THREADS=$threads timed $eb -style "${style[$name]}" "${eb_args[@]}" -output "$file"
    else
      timed $ex stylize --style "${style[$name]}" "${ex_args[@]}" -o "$file" -j "$threads" -q \
        "${extra[@]}"
    fi
    secs_of[$tool]=$secs
    read -r texture fidelity < <($measure "$name" "$threads" 1 --measure "$file" |
      awk '{ for (i = 1; i < NF; ++i) { if ($i == "texture") t = $(i + 1); if ($i == "fidelity") f = $(i + 1) } } END { print t, f }')
    speed=$(awk -v e="${secs_of[ebsynth]}" -v s="$secs" 'BEGIN { printf "%.1f", e / s }')
    printf "%-10s %-9s %8s %8s %9s %8s %9s\n" "$name" "$tool" "$secs" "$speed" "$mib" "$texture" "$fidelity"
  done
done
echo "outputs: $out/ (extra exemplar flags: ${extra[*]:-none})"
