#!/bin/bash
# The manual stays walkable: the README is a front page (at most 300 lines)
# from which every page of docs/ is linked, and every relative link of the
# README, the CHANGELOG and docs/ leads to a file that exists.
#   tests/docs/docs_links_test.sh SOURCE_DIR
set -euo pipefail
root=$(cd "${1:?usage: docs_links_test.sh SOURCE_DIR}" && pwd)
cd "$root"
status=0
lines=$(wc -l <README.md)
if [ "$lines" -gt 300 ]; then
  echo "README.md has $lines lines, more than 300: move the detail into docs/" >&2
  status=1
fi
while IFS= read -r page; do
  if ! grep -q "($page)" README.md; then
    echo "$page is not linked from README.md" >&2
    status=1
  fi
done < <(find docs -name '*.md' | sort)
while IFS= read -r file; do
  dir=$(dirname "$file")
  # Markdown links [text](target), the target without an #anchor.
  while IFS= read -r target; do
    case "$target" in http://* | https://* | mailto:* | '#'*) continue ;; esac
    target=${target%%#*}
    if [ ! -e "$dir/$target" ]; then
      echo "$file links to $target, which does not exist" >&2
      status=1
    fi
  done < <(grep -o '\](\([^)]*\))' "$file" | sed 's/^](\(.*\))$/\1/')
done < <(printf '%s\n' README.md CHANGELOG.md; find docs -name '*.md' | sort)
exit $status
