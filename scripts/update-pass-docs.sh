#!/usr/bin/env bash
# Regenerates the parameter and pin tables in every pass README from the pass declarations
# (`pathlet passes --describe TYPE --markdown`), between the lines
#   <!-- pathlet passes --describe TYPE --markdown -->   and   <!-- end of generated tables -->
# and the index of passes/README.md (`pathlet passes --markdown`, between
#   <!-- pathlet passes --markdown --> and the same end line), so the docs cannot drift from the
# code. The test PassDocs.ReadmeTablesMatchTheDeclarations checks that they match.
set -euo pipefail
cd "$(dirname "$0")/.."
PATHLET=${PATHLET:-build/bin/pathlet}
# Replaces the lines between the marker $2 and the end marker of file $1 with $3.
splice() {
  local tmp
  # Both markers, in order: without the end line everything after the start would be lost.
  if ! awk -v marker="$2" '$0 == marker { m = 1 } m && /^<!-- end of generated tables -->$/ { ok = 1 } END { exit !ok }' "$1"; then
    echo "$1: needs the line '$2' and, after it, '<!-- end of generated tables -->'" >&2
    return 1
  fi
  tmp=$(mktemp "$1.XXXXXX")
  trap 'rm -f "$tmp"' RETURN
  chmod --reference="$1" "$tmp"
  awk -v marker="$2" -v tables="$3" '
    $0 == marker { print; print ""; print tables; skip = 1; next }
    /^<!-- end of generated tables -->$/ { skip = 0; print ""; print; next }
    !skip { print }' "$1" >"$tmp"
  if cmp -s "$tmp" "$1"; then rm "$tmp"; else mv "$tmp" "$1"; echo "updated $1"; fi
}
splice passes/README.md "<!-- pathlet passes --markdown -->" "$("$PATHLET" passes --markdown)"
for readme in passes/*/README.md; do
  type=$(sed -n 's/^<!-- pathlet passes --describe \([a-z0-9_]*\) --markdown -->$/\1/p' "$readme" | head -1)
  if [ -z "$type" ]; then echo "update-pass-docs: $readme has no generated-table marker" >&2; continue; fi
  splice "$readme" "<!-- pathlet passes --describe $type --markdown -->" "$("$PATHLET" passes --describe "$type" --markdown)"
done
