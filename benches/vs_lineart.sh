#!/usr/bin/env bash
# Whole-process times of sightline beside Blender's Line Art, the comparison issue 13 sets its
# targets by: bunny and dragon (../shared/meshes) and the 1M-triangle sphere file that
# ../shared/compare/scenes.py writes, two rounds. Read ratios within one run: these machines are
# shared and noisy, absolute seconds from different runs do not compare.
#
# usage: benches/vs_lineart.sh [SIGHTLINE [OTHER_SIGHTLINE]]
#   SIGHTLINE defaults to target/release/sightline (build it first: cargo build --release);
#   OTHER_SIGHTLINE, when given, is timed beside it (say, the binary of an older commit).
#   SIGHTLINE_SHARED overrides the path of ../shared.
#
# Per mesh: Line Art's visible lines (lineart.py --no-hidden: cold and warm seconds), its
# visible and hidden lines, then per binary the whole `render --method bsp -o x.svg` (seconds,
# peak RSS, bytes per triangle), `render` (auto), `lines`, and on dragon `render --method
# zbuffer` at 4096x4096. Needs blender (apt-get install blender); what is missing is said and
# skipped.
set -u
here=$(cd "$(dirname "$0")/.." && pwd)
shared=${SIGHTLINE_SHARED:-$here/../shared}
binaries=("${1:-$here/target/release/sightline}")
[ $# -ge 2 ] && binaries+=("$2")
for b in "${binaries[@]}"; do
    [ -x "$b" ] || { echo "no sightline binary at $b (cargo build --release)" >&2; exit 1; }
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The scenes: (name, obj, cam), made where needed.
scenes=()
m=$shared/meshes
if [ -f "$m/bunny.obj" ]; then scenes+=("bunny $m/bunny.obj $m/cams/bunny.cam"); else
    echo "absent: $m/bunny.obj (bunny skipped)"; fi
if [ -f "$m/dragon.obj.gz" ]; then
    gunzip -c "$m/dragon.obj.gz" > "$work/dragon.obj"
    scenes+=("dragon $work/dragon.obj $m/cams/dragon.cam")
else echo "absent: $m/dragon.obj.gz (dragon skipped)"; fi
if [ -f "$shared/compare/scenes.py" ]; then
    python3 "$shared/compare/scenes.py" "$work/scenes" > /dev/null
    s=$work/scenes/sphere_1000000
    scenes+=("sphere_1000000 $s.obj $s.cam")
else echo "absent: $shared/compare/scenes.py (the 1M sphere skipped)"; fi

has_blender=1
command -v blender > /dev/null && [ -f "$shared/compare/lineart.py" ] || {
    has_blender=0
    echo "absent: blender or $shared/compare/lineart.py (Line Art not timed)"
}

# `/usr/bin/time` prints "<seconds> s <KiB> KiB" last on stderr.
timed() { { /usr/bin/time -f '%e s %M KiB' "$@" > /dev/null 2> "$work/err"; } 2>&1;
    tail -1 "$work/err"; }

for round in 1 2; do
    for scene in "${scenes[@]}"; do
        read -r name obj cam <<< "$scene"
        triangles=$(awk '$1 == "f" { t += NF - 3 } END { print t }' "$obj")
        if [ $has_blender = 1 ]; then
            la() { (cd "$shared/compare" && blender -b --factory-startup --python lineart.py \
                -- "$obj" "$cam" "$work/la.svg" --no-bl-svg "$@" 2>&1 | grep LA_RESULT); }
            visible=$(la --no-hidden | grep -o 'lineart_vis_\(cold\|warm\)_s=[0-9.]*' | tr '\n' ' ')
            both=$(la | grep -o 'lineart_vis_hid_s=[0-9.]*')
            echo "round $round $name ($triangles triangles): Line Art $visible$both"
        fi
        for b in "${binaries[@]}"; do
            bsp=$(timed "$b" render "$obj" --cam "$cam" --method bsp -o "$work/x.svg")
            per=$(awk -v k="$(echo "$bsp" | awk '{ print $3 }')" -v t="$triangles" \
                'BEGIN { printf "%.0f", k * 1024 / t }')
            auto=$(timed "$b" render "$obj" --cam "$cam" -o "$work/x.svg" | cut -d' ' -f1-2)
            lines=$(timed "$b" lines "$obj" --cam "$cam" -o "$work/l.svg")
            line="round $round $name $b: bsp $bsp ($per B/triangle) | auto $auto | lines $lines"
            if [ "$name" = dragon ]; then
                zb=$(timed "$b" render "$obj" --cam "$cam" --method zbuffer --size 4096x4096 \
                    -o "$work/z.png" | cut -d' ' -f1-2)
                line="$line | zbuffer 4096x4096 $zb"
            fi
            echo "$line"
        done
    done
done
