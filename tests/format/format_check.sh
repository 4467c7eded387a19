#!/usr/bin/env bash
# Checks that every C++ source and header of the tree is formatted as .clang-format says, with the
# clang-format of packages.txt (clang-format-14: another version formats some lines otherwise).
#
#   format_check.sh SOURCE_DIR
#
# Lists the files that differ and exits 1; to fix them: clang-format-14 -i <file>...
# The files are git's tracked ones when SOURCE_DIR is a git checkout, else every *.cpp and *.h
# outside build folders. Fuzz corpora are inputs, not sources, and are left out.
set -euo pipefail
if [ $# -ne 1 ]; then
  echo "usage: $0 SOURCE_DIR" >&2
  exit 2
fi
cd "$1"
formatter=clang-format-14
if ! command -v "$formatter" >/dev/null; then
  echo "format_check: $formatter not found: install clang-format-14 (packages.txt)" >&2
  exit 1
fi
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  mapfile -t files < <(git ls-files '*.cpp' '*.h' | grep -v '^fuzz/corpus/')
else
  mapfile -t files < <(find . -path './build*' -prune -o -path './fuzz/corpus' -prune -o \
                         -type f \( -name '*.cpp' -o -name '*.h' \) -print | sed 's|^\./||')
fi
unformatted=()
for f in "${files[@]}"; do
  [ -f "$f" ] || continue  # (deleted in the working tree, not yet in git)
  if ! "$formatter" --style=file --dry-run --Werror "$f" >/dev/null 2>&1; then unformatted+=("$f"); fi
done
if [ ${#unformatted[@]} -gt 0 ]; then
  echo "format_check: ${#unformatted[@]} of ${#files[@]} files are not formatted as .clang-format says:" >&2
  printf '  %s\n' "${unformatted[@]}" >&2
  echo "fix: $formatter -i <file>..." >&2
  exit 1
fi
echo "format_check: ${#files[@]} files formatted"
