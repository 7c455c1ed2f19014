#!/bin/sh
# Seeds the cargo-fuzz corpora from the shipped files (docs/fuzzing.md), from the repository root:
#   fuzz/corpus/design_file/  designs/*.toml
#   fuzz/corpus/dxf_import/   the DXF of every shipped design (dlw draw)
#   fuzz/corpus/recording/    short simulated recordings of Joints A and C, rig.toml NUL data.csv
set -eu
cd "$(dirname "$0")/.."
cargo build -q
dlw=target/debug/dlw
for t in design_file dxf_import recording; do mkdir -p "fuzz/corpus/$t"; done
cp designs/joint-*.toml fuzz/corpus/design_file/
for d in designs/joint-*.toml; do
  stem=$(basename "$d" .toml)
  "$dlw" draw "$d" --dxf "fuzz/corpus/dxf_import/$stem.dxf" >/dev/null 2>&1
done
tmp=$(mktemp -d)
for j in a c; do
  "$dlw" simulate --design "designs/joint-$j.toml" --protocol random --seed 1 --duration-s 0.2 \
    -o "$tmp/rec-$j" >/dev/null
  { cat "$tmp/rec-$j/rig.toml"; printf '\000'; cat "$tmp/rec-$j/data.csv"; } \
    > "fuzz/corpus/recording/joint-$j.rec"
done
rm -rf "$tmp"
ls -l fuzz/corpus/*
