#!/usr/bin/env bash
# Regenerates the parameter and pin tables in every pass README from the pass declarations
# (`pathlet passes --describe TYPE --markdown`), between the lines
#   <!-- pathlet passes --describe TYPE --markdown -->   and   <!-- end of generated tables -->
# so the docs cannot drift from the code. tests/docs checks that they match.
set -euo pipefail
cd "$(dirname "$0")/.."
PATHLET=${PATHLET:-build/bin/pathlet}
for readme in passes/*/README.md; do
  type=$(sed -n 's/^<!-- pathlet passes --describe \([a-z0-9_]*\) --markdown -->$/\1/p' "$readme" | head -1)
  if [ -z "$type" ]; then echo "update-pass-docs: $readme has no generated-table marker" >&2; continue; fi
  tables=$("$PATHLET" passes --describe "$type" --markdown)
  tmp=$(mktemp "$readme.XXXXXX")
  awk -v tables="$tables" '
    /^<!-- pathlet passes --describe [a-z0-9_]+ --markdown -->$/ { print; print ""; print tables; skip = 1; next }
    /^<!-- end of generated tables -->$/ { skip = 0; print ""; print; next }
    !skip { print }' "$readme" >"$tmp"
  if cmp -s "$tmp" "$readme"; then rm "$tmp"; else mv "$tmp" "$readme"; echo "updated $readme"; fi
done
