#!/usr/bin/env bash
# Lists the longest C++ functions (lambdas included) in filters/ and app/, longest first, and the
# longest core sources, with universal-ctags:
#   bash scripts/longest-functions.sh [COUNT]     the COUNT longest of each (default 20)
#   bash scripts/longest-functions.sh --check     exits 1 if a function is over 150 lines or a
#                                                 core source over 1,000 (the layout's limits)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
max_function=150
max_source=1000
check=0
count=20
if [ "${1:-}" = "--check" ]; then check=1; else count="${1:-20}"; fi
if ! ctags --version 2>/dev/null | grep -q "Universal Ctags"; then
  echo "longest-functions: needs universal-ctags (apt-get install universal-ctags)" >&2
  exit 2
fi
ctags -R --languages=C++ --kinds-C++=f --fields=+ne --output-format=json -o - filters app |
  /usr/bin/python3 -c '
import json, pathlib, sys
count, check, max_function, max_source = map(int, sys.argv[1:5])
rows = []
for line in sys.stdin:
    tag = json.loads(line)
    if tag.get("kind") == "function" and "end" in tag:
        name = (tag["scope"] + "::" if tag.get("scope") else "") + tag["name"]
        rows.append((tag["end"] - tag["line"] + 1, tag["path"], tag["line"], name))
rows.sort(key=lambda r: -r[0])
sources = sorted(((len(p.read_text().splitlines()), str(p))
                  for p in pathlib.Path("filters/core").rglob("*") if p.suffix in (".cpp", ".h")),
                 reverse=True)
if check:
    long_functions = [r for r in rows if r[0] > max_function]
    long_sources = [s for s in sources if s[0] > max_source]
    for n, path, line, name in long_functions:
        print(f"{path}:{line}: {name} has {n} lines (at most {max_function})")
    for n, path in long_sources:
        print(f"{path}: {n} lines (at most {max_source} in the core)")
    if long_functions or long_sources:
        sys.exit(1)
    print(f"{len(rows)} functions, none over {max_function} lines (longest {rows[0][0]}: "
          f"{rows[0][3]}); {len(sources)} core sources, none over {max_source} lines")
    sys.exit(0)
print("longest functions in filters/ and app/:")
for n, path, line, name in rows[:count]:
    print(f"{n:6d}  {path}:{line}  {name}")
print("longest core sources:")
for n, path in sources[:count]:
    print(f"{n:6d}  {path}")
' "$count" "$check" "$max_function" "$max_source"
