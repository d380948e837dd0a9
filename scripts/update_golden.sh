#!/usr/bin/env bash
# Regenerates the golden images tests/golden/*.png, which test_scenes (Golden/GoldenImage.*)
# compares every render with, from a built luz:
#
#     scripts/update_golden.sh [LUZ]        # LUZ defaults to build/release/luz
#
# Each line of tests/golden/cases.txt is NAME then the arguments of `luz` (split at blanks, no
# quoting); NAME.png is what `luz ARGS -o NAME.png` writes. Every case is rendered first, so a
# failure leaves tests/golden/ as it was; then the PNGs are replaced and stale ones removed.
# Run it only when a change of picture is intended, look at the new images (`git status`
# shows which changed) and commit them with the change that explains them.
set -euo pipefail
cd "$(dirname "$0")/.."
luz="${1:-build/release/luz}"
if [ ! -x "$luz" ]; then
  echo "update_golden.sh: no luz binary at $luz (cmake --preset release && cmake --build --preset release)" >&2
  exit 1
fi
luz="$(realpath "$luz")"
golden=tests/golden
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

count=0
while read -r -a words; do
  [ "${#words[@]}" -eq 0 ] && continue
  [[ "${words[0]}" == \#* ]] && continue
  name="${words[0]}"
  (cd "$tmp" && "$luz" "${words[@]:1}" -o "$name.png")
  count=$((count + 1))
done < "$golden/cases.txt"

rm -f "$golden"/*.png
mv "$tmp"/*.png "$golden"/
bytes="$(cat "$golden"/*.png | wc -c)"
echo "wrote $count images to $golden ($bytes bytes)"
