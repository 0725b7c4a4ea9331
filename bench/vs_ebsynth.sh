#!/usr/bin/env bash
# Side by side with ebsynth (issue 15): ebsynth's public-domain CPU build, compiled here from
# ../shared/anchors/ebsynth with the line of its build-linux-cpu_only.sh (into build/, never
# copied into the project), and `exemplar stylize` on the same inputs and guide weights (the
# ebsynth authors' weights, ../shared/data/SOURCES.md), one after the other with the same thread
# count. Prints per example and tool: wall time, peak RSS (/usr/bin/time), texture kept and
# patch fidelity (bench_examples --measure), and the ratios against ebsynth. Outputs stay in
# build/vs_ebsynth/ to look at.
#
# inpaint3 (texture-synthesis' inpainting example: fill the red "Z" painted over 3.jpg's birch
# bark, where masks/3_inpaint.jpg is black) is `exemplar stylize --inpaint`: only the hole is
# synthesized, from patches entirely outside it, and the rest is kept. ebsynth has no masks and
# redraws the whole target, so it gets the fairest formulation found with guides (written by
# `bench_examples inpaint3 --write-guides`), each pair the same image on both sides unless said:
#   filled, weight 0.1: 3.jpg with the hole at the known pixels' mean colour (pins the known
#     region to itself; heavier, it pins the hole to a flat colour: weight 1 left a grey Z,
#     texture 0.20 in the hole);
#   smooth, weight 1: the known colours spread over the hole (normalized Gaussian convolution,
#     sigma 8 px), the low frequencies of the surroundings on both sides, so that the hole takes
#     bark of the right tone without favouring flat patches;
#   hole -> none, weight 10: 1 in the hole on the source side, 0 on the target side, so that a
#     source patch overlapping the Z costs 10 per hole pixel (forbids copying the Z back).
# No formulation is fully fair: without per-pixel weights a guide that keeps the known region
# flattens the hole and one that frees the hole lets the known region drift. Both outputs are
# measured after pasting them into the hole of 3.jpg (what an ebsynth user would keep; exemplar's
# output is unchanged by it): texture kept and fidelity inside the hole against the known region,
# and "outside" = the largest change (of 255) outside the hole before pasting.
#
# Usage: [EXAMPLES="name ..."] bash bench/vs_ebsynth.sh [threads] [extra exemplar flags...]
#   bash bench/vs_ebsynth.sh 2                    # default quality, every example
#   bash bench/vs_ebsynth.sh 2 --quality best     # compare a preset (or any stylize flags)
#   EXAMPLES=inpaint3 bash bench/vs_ebsynth.sh 2  # some of stylit facestyle texbynum guided2
#                                                 # inpaint3
set -euo pipefail
cd "$(dirname "$0")/.."
threads=${1:-2}
shift || true
extra=("$@")  # extra exemplar flags
examples=${EXAMPLES:-stylit facestyle texbynum guided2 inpaint3}
anchor=../shared/anchors/ebsynth
data=../shared/data/guided/ebsynth
if [[ ! -f $anchor/src/ebsynth.cpp || ! -d $data || ! -d $data/../texture-synthesis ]]; then
  echo "vs_ebsynth: $anchor or $data(/../texture-synthesis) is absent (optional benchmark data);" \
    "nothing compared"
  exit 0
fi
for name in $examples; do
  case $name in
    stylit | facestyle | texbynum | guided2 | inpaint3) ;;
    *)
      echo "vs_ebsynth: EXAMPLES: unknown example '$name' (stylit facestyle texbynum guided2" \
        "inpaint3)" >&2
      exit 1
      ;;
  esac
done
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
# Inpainting (EmbarkStudios/texture-synthesis imgs/3.jpg): ebsynth's guides, see the top.
style[inpaint3]=$data/../texture-synthesis/3.jpg
guides[inpaint3]="filled 0.1 smooth 1 hole 10"

# Runs "$@" under /usr/bin/time; sets secs and mib.
timed() {
  local log=$out/time.txt
  /usr/bin/time -f "%e %M" -o $log "$@" > /dev/null 2>> $out/stderr.txt
  read -r secs kb < $log
  mib=$(awk -v k="$kb" 'BEGIN { printf "%.0f", k / 1024 }')
}

printf "%-10s %-9s %8s %8s %9s %8s %9s %8s\n" example tool "time s" "x eb" "RSS MiB" texture \
  fidelity outside
for name in $examples; do
  eb_args=() ex_args=()
  if [[ $name == inpaint3 ]]; then
    $measure inpaint3 "$threads" 1 --write-guides $out
    ex_args=(--inpaint "$data/../texture-synthesis/masks/3_inpaint.jpg")
  fi
  set -- ${guides[$name]}
  while (($# > 0)); do
    if [[ $name == guided2 ]]; then
      s=$data/../texture-synthesis/masks/2_example.jpg t=$data/../texture-synthesis/masks/2_target.jpg
    elif [[ $name == inpaint3 ]]; then
      s=$out/inpaint3_$1.png
      t=$s
      [[ $1 == hole ]] && t=$out/inpaint3_none.png
    else
      s=$data/$name/source_$1.png t=$data/$name/target_$1.png
    fi
    eb_args+=(-guide "$s" "$t" -weight "$2")
    [[ $name == inpaint3 ]] || ex_args+=(--guide "$s" "$t" --weight "$2")
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
    read -r texture fidelity outside < <($measure "$name" "$threads" 1 --measure "$file" |
      awk '{ o = "-"; for (i = 1; i < NF; ++i) { if ($i == "texture") t = $(i + 1); if ($i == "fidelity") f = $(i + 1); if ($i == "outside") o = $(i + 1) } } END { print t, f, o }')
    speed=$(awk -v e="${secs_of[ebsynth]}" -v s="$secs" 'BEGIN { printf "%.1f", e / s }')
    printf "%-10s %-9s %8s %8s %9s %8s %9s %8s\n" "$name" "$tool" "$secs" "$speed" "$mib" "$texture" \
      "$fidelity" "$outside"
  done
done
echo "outputs: $out/ (extra exemplar flags: ${extra[*]:-none})"
