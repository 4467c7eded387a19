#!/usr/bin/env bash
# Runs every shell command block of the user documentation, so that the docs stay true.
#
#   run_doc_commands.sh SOURCE_DIR BINARY_DIR [FILE.md ...]
#
# Which blocks: every fenced block opened by ```sh in README.md and docs/*.md (or in the files
# given), except
#   - the README's two set-up commands, the blocks right after <!-- demo-command --> and
#     <!-- test-command --> (they install packages and build everything; CI runs the second);
#   - a block whose previous non-blank line is <!-- doc-test: skip (reason) -->. The reason is
#     required (why the block cannot run here: minutes of benchmark, writes to a system prefix,
#     rebuilds the project ...); a skip marker without one is an error.
#
# How a block runs (the convention the docs are written in): as a user runs it from the
# repository root after the README's set-up command, i.e. with the build in `build/`.
#   - Each block runs with `bash -euo pipefail` in a fresh temporary directory that holds a
#     symbolic link to every top-level entry of the repository (robots, tools, bench, ...) and
#     `build` -> BINARY_DIR. So `build/tools/deepcheck info robots/data/...` works as written,
#     and the files a block writes (path.txt, pieces.obj) land in the temporary directory, never
#     in the repository.
#   - The `deepcheck` program and the examples are also on the PATH (as after an install).
#   - XDG_CACHE_HOME is BINARY_DIR/doc_test_cache: convex decompositions are cached across blocks
#     and runs, and the user's own cache is not touched.
#   - Each block must finish within DOC_TEST_TIMEOUT seconds (default 120): docs show commands
#     that take seconds; longer ones are marked skip with their reason.
# A failing block is reported as FILE:LINE (the line of its opening fence) with its output, and
# the script exits 1 after running the others. Exit status 2 for a bad command line or marker.
set -uo pipefail

if [ $# -lt 2 ]; then
  echo "usage: $0 SOURCE_DIR BINARY_DIR [FILE.md ...]" >&2
  exit 2
fi
source_dir=$(cd "$1" && pwd) || exit 2
binary_dir=$(cd "$2" && pwd) || exit 2
shift 2
if [ $# -gt 0 ]; then
  files=("$@")
else
  shopt -s nullglob
  files=("$source_dir/README.md" "$source_dir"/docs/*.md)
  shopt -u nullglob
fi
timeout_s=${DOC_TEST_TIMEOUT:-120}

export PATH="$binary_dir/tools:$binary_dir/examples:$PATH"
export XDG_CACHE_HOME="$binary_dir/doc_test_cache"
mkdir -p "$XDG_CACHE_HOME"

work=$(mktemp -d "${TMPDIR:-/tmp}/deepcheck_doc_test.XXXXXX")
trap 'rm -rf "$work"' EXIT

ran=0
skipped=0
failed=0

# A temporary directory that looks like the repository root after the set-up command.
make_root() {
  local dir=$1 entry
  mkdir -p "$dir"
  for entry in "$source_dir"/* "$source_dir"/.[!.]*; do
    [ -e "$entry" ] || continue
    case $(basename "$entry") in
      build | .git) continue ;;
    esac
    ln -s "$entry" "$dir/$(basename "$entry")"
  done
  ln -s "$binary_dir" "$dir/build"
}

# Runs one block; $1 file, $2 line of the opening fence, $3 the block's text.
run_block() {
  local file=$1 line=$2 text=$3 rel dir
  rel=${file#"$source_dir"/}
  ran=$((ran + 1))
  dir="$work/block_$ran"
  make_root "$dir"
  printf '%s\n' "$text" >"$work/block_$ran.sh"
  echo "== $rel:$line"
  if (cd "$dir" && timeout --kill-after=10 "$timeout_s" bash -euo pipefail "$work/block_$ran.sh") >"$work/block_$ran.out" 2>&1; then
    echo "   ok"
  else
    local status=$?
    failed=$((failed + 1))
    echo "FAIL $rel:$line (exit status $status$([ "$status" = 124 ] && echo ", over ${timeout_s} s"))"
    sed 's/^/   | /' "$work/block_$ran.sh"
    echo "   output:"
    sed 's/^/   > /' "$work/block_$ran.out"
  fi
}

# Walks one Markdown file: fences, markers and the blocks to run.
scan_file() {
  local file=$1 rel number=0 previous="" in_block=0 kind="" start=0 text="" skip=0 line trimmed
  rel=${file#"$source_dir"/}
  while IFS= read -r line || [ -n "$line" ]; do
    number=$((number + 1))
    trimmed=${line#"${line%%[![:space:]]*}"}
    if [ "$in_block" = 1 ]; then
      if [[ $trimmed == '```'* ]]; then
        in_block=0
        if [ "$kind" = sh ]; then
          if [ "$skip" = 1 ]; then
            skipped=$((skipped + 1))
          else
            run_block "$file" "$start" "$text"
          fi
        fi
        previous=$line
      elif [ "$kind" = sh ]; then
        text+="$line"$'\n'
      fi
      continue
    fi
    if [[ $trimmed == '```'* ]]; then
      in_block=1
      kind=${trimmed#'```'}
      kind=${kind%%[[:space:]]*}
      start=$number
      text=""
      skip=0
      case $previous in
        *'<!-- demo-command -->'* | *'<!-- test-command -->'*) skip=1 ;;
        *'<!-- doc-test: skip ('?*') -->'*) skip=1 ;;
        *'<!-- doc-test:'*)
          echo "BAD MARKER $rel:$((number - 1)): write <!-- doc-test: skip (reason) -->" >&2
          exit 2
          ;;
      esac
      continue
    fi
    [ -n "$trimmed" ] && previous=$trimmed
  done <"$file"
  if [ "$in_block" = 1 ]; then
    echo "UNCLOSED BLOCK $rel:$start" >&2
    exit 2
  fi
}

for file in "${files[@]}"; do
  if [ ! -f "$file" ]; then
    echo "no such file: $file" >&2
    exit 2
  fi
  scan_file "$(cd "$(dirname "$file")" && pwd)/$(basename "$file")"
done

echo "doc blocks: $ran run, $failed failed, $skipped skipped (marked)"
[ "$failed" = 0 ]
