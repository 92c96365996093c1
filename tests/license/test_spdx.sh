#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-2-Clause
# The code's licence: LICENSE is BSD-2-Clause, and every source file of the
# tree names it in an SPDX line (scripts/spdx-check). The check itself is
# tried on a small tree of its own: it must name a file without the line,
# and --add must add it without changing anything else.
set -u
cd "$(dirname "$0")/../.."
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
pass=0
fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }

head -1 LICENSE | grep -qx "BSD 2-Clause License" && ok || bad "LICENSE is not BSD-2-Clause"
grep -qx "Copyright (c) 2026 The brdfwave authors" LICENSE && ok || bad "LICENSE: no copyright line"
grep -q "^2. Redistributions in binary form" LICENSE && ok || bad "LICENSE: not the whole text"

# the tree
scripts/spdx-check >"$T/out" 2>&1 && ok || bad "sources without an SPDX line: $(head -20 "$T/out")"
n=$(git ls-files | grep -cE '\.(c|h|py|sh|mk|ld)$|(^|/)Makefile$')
[ "$n" -gt 200 ] && ok || bad "only $n source files seen"

# the check on a tree of its own
mkdir -p "$T/tree/scripts" "$T/tree/src" "$T/tree/tests/data"
cp scripts/spdx-check "$T/tree/scripts/"
(
    cd "$T/tree" || exit 1
    git init -q . && git config user.email t@example.org && git config user.name t
    printf '/* SPDX-License-Identifier: BSD-2-Clause */\nint a;\n' >src/good.c
    printf '/* a file without one */\nint b;\n' >src/bad.c
    printf '#!/bin/sh\necho hi\n' >src/run.sh
    chmod +x src/run.sh
    printf 'all:\n\ttrue\n' >Makefile
    printf 'int data;\n' >tests/data/third_party.c # the data keep their own licences
    printf '# SPDX-License-Identifier: BSD-2-Clause\n' >scripts/spdx-extra
    git add -A && git commit -q -m t
    printf 'x = 1\n' >src/new.py # not yet added: still checked
)
"$T/tree/scripts/spdx-check" >"$T/out" 2>"$T/err"
rc=$?
[ "$rc" = 1 ] && ok || bad "a tree with files lacking the line: exit $rc"
sort "$T/out" | sed 's/: .*//' >"$T/named"
printf '%s\n' Makefile src/bad.c src/new.py src/run.sh >"$T/want"
cmp -s "$T/named" "$T/want" && ok || bad "named: $(cat "$T/named" | tr '\n' ' ')"
grep -q "4 source file(s)" "$T/err" && ok || bad "stderr: $(cat "$T/err")"
"$T/tree/scripts/spdx-check" "$T/tree/src/good.c" && ok || bad "a good file given by name"
"$T/tree/scripts/spdx-check" "$T/tree/src/bad.c" >/dev/null 2>&1 && bad "a bad file given by name passed" || ok
"$T/tree/scripts/spdx-check" "$T/tree/nosuch.c" 2>"$T/err" >/dev/null
[ $? = 2 ] && grep -q "no such file" "$T/err" && ok || bad "a missing file: $(cat "$T/err")"

"$T/tree/scripts/spdx-check" --add >/dev/null && ok || bad "--add"
"$T/tree/scripts/spdx-check" >/dev/null 2>&1 && ok || bad "after --add the check still fails"
[ "$(head -1 "$T/tree/src/run.sh")" = "#!/bin/sh" ] &&
    [ "$(sed -n 2p "$T/tree/src/run.sh")" = "# SPDX-License-Identifier: BSD-2-Clause" ] &&
    [ "$(sed -n 3p "$T/tree/src/run.sh")" = "echo hi" ] && [ -x "$T/tree/src/run.sh" ] && ok ||
    bad "--add on a script: $(cat "$T/tree/src/run.sh")"
printf '/* SPDX-License-Identifier: BSD-2-Clause */\n/* a file without one */\nint b;\n' |
    cmp -s - "$T/tree/src/bad.c" && ok || bad "--add on C: $(cat "$T/tree/src/bad.c")"
printf '# SPDX-License-Identifier: BSD-2-Clause\nall:\n\ttrue\n' | cmp -s - "$T/tree/Makefile" && ok ||
    bad "--add on the Makefile: $(cat "$T/tree/Makefile")"
[ "$(cat "$T/tree/tests/data/third_party.c")" = "int data;" ] && ok || bad "--add changed the data"
"$T/tree/scripts/spdx-check" --add | grep -q . && bad "a second --add changed something" || ok

echo "RESULT: $pass passed, $fail failed"
[ "$fail" = 0 ]
