#!/bin/sh
# Writes a copy of a shared scene at another film resolution and maximum depth, next to links
# to the original's assets, for equal-time benchmarks that need long references:
#   bench/scenes/small-copy.sh SCENE.pbrt WIDTH HEIGHT MAXDEPTH OUTDIR
# prints the path of the copy.
set -eu
src=$1 w=$2 h=$3 depth=$4 out=$5
mkdir -p "$out"
for f in "$(dirname "$src")"/*; do
  [ "$f" = "$src" ] || ln -sfn "$(realpath "$f")" "$out/$(basename "$f")"
done
dst="$out/$(basename "$src" .pbrt)-${w}x${h}.pbrt"
sed -e "s/\"integer xresolution\" \[ *[0-9]* *\]/\"integer xresolution\" [ $w ]/" \
    -e "s/\"integer yresolution\" \[ *[0-9]* *\]/\"integer yresolution\" [ $h ]/" \
    -e "s/\"integer maxdepth\" \[ *[0-9]* *\]/\"integer maxdepth\" [ $depth ]/" "$src" > "$dst"
echo "$dst"
