#!/usr/bin/env bash
# Every C++ file of the tree is formatted with the project's .clang-format (run scripts/indent).
set -u
cd "$ESTEP_SOURCE_DIR"
command -v clang-format > /dev/null || { echo "clang-format is not installed"; exit 1; }
bad=()
while IFS= read -r file; do
  clang-format --dry-run -Werror "$file" > /dev/null 2>&1 || bad+=("$file")
done < <(git ls-files '*.h' '*.cc' 2>/dev/null || find include source tests benchmarks -name '*.h' -o -name '*.cc')
if ((${#bad[@]})); then
  printf 'Not formatted (run scripts/indent): %s\n' "${bad[@]}"
  exit 1
fi
echo "all files formatted"
