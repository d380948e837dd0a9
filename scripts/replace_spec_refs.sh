#!/usr/bin/env bash
# Replaces the code's references to the old contract ("SPEC §1.1" …) and to README sections by
# the docs/ page that now holds them, following docs/notes/spec_refs.tsv (old text TAB new text,
# applied in file order).
# Usage: scripts/replace_spec_refs.sh [DIR_OR_FILE …]   (default: src include tests bench scripts cmake)
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
table="$root/docs/notes/spec_refs.tsv"
cd "$root"
if [ "$#" -eq 0 ]; then set -- src include tests bench scripts cmake; fi

# One sed expression per row. The old text is matched literally (regex characters escaped);
# one ending in a section number must not be followed by more of a number ("SPEC §1" leaves
# "SPEC §1.6" alone), so a later, shorter row never eats a longer reference.
script="$(mktemp)"
trap 'rm -f "$script"' EXIT
while IFS=$'\t' read -r old new; do
    [ -n "$old" ] || continue
    pattern="$(printf '%s' "$old" | sed -e 's/[]\/$*.^|?+(){}[]/\\&/g')"
    replacement="$(printf '%s' "$new" | sed -e 's/[\/&]/\\&/g')"
    if [[ "$old" =~ [0-9]$ ]]; then
        printf 's/%s($|[^.0-9]|\\.($|[^0-9]))/%s\\1/g\n' "$pattern" "$replacement" >> "$script"
    else
        printf 's/%s/%s/g\n' "$pattern" "$replacement" >> "$script"
    fi
done < "$table"

# C++ files that clang-format leaves as they are get clang-format again after the change (the
# longer text may pass the 100-column limit); the others are only edited.
self="scripts/replace_spec_refs.sh"
changed=0
while IFS= read -r -d '' file; do
    [ "$file" != "$self" ] || continue
    clean=0
    if [[ "$file" =~ \.(h|cpp)$ ]] && command -v clang-format > /dev/null &&
        clang-format "$file" | cmp -s - "$file"; then
        clean=1
    fi
    before="$(md5sum < "$file")"
    sed -E -i -f "$script" "$file"
    if [ "$(md5sum < "$file")" != "$before" ]; then
        changed=$((changed + 1))
        [ "$clean" -eq 0 ] || clang-format -i "$file"
    fi
done < <(grep -rlIZ -e 'SPEC' -e '§' -e 'README' -- "$@" || true)

echo "replace_spec_refs: $changed files changed"
left="$(grep -rnI -e 'SPEC §' -e 'SPEC [0-9]' -e 'SPEC section' -- "$@" | grep -v "^$self:" || true)"
if [ -n "$left" ]; then
    echo "replace_spec_refs: references left (not in $table):" >&2
    echo "$left" >&2
    exit 1
fi
