#!/usr/bin/env bash
# The README's code blocks marked `<!-- example: FILE -->` are FILE's own text
# between its `[readme]` and `[/readme]` marker lines (the common indentation
# removed), so that the README shows code that compiles and runs (examples/,
# built and run by the tests). Usage: check_readme_examples.sh SOURCE_ROOT
set -euo pipefail
root="${1:-.}"
exec python3 - "$root" <<'PY'
import re, sys, textwrap
root = sys.argv[1]
readme = open(f"{root}/README.md").read()
blocks = re.findall(r"<!-- example: (\S+) -->\n```\w*\n(.*?)```", readme, re.S)
if not blocks:
    sys.exit("README.md: no <!-- example: FILE --> block")
bad = 0
for path, block in blocks:
    text = open(f"{root}/{path}").read()
    m = re.search(r"^[^\n]*\[readme\][^\n]*\n(.*?)^[^\n]*\[/readme\]", text, re.S | re.M)
    if not m:
        print(f"{path}: no [readme] ... [/readme] markers"); bad = 1; continue
    if textwrap.dedent(m.group(1)).strip() != block.strip():
        print(f"README.md: the block from {path} differs from the file's [readme] part"); bad = 1
print("README examples: " + ("FAILED" if bad else f"OK ({len(blocks)} blocks)"))
sys.exit(bad)
PY
