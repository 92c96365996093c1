#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-2-Clause
# The Python package as a user installs it: a clean virtual environment
# (Debian's numpy through --system-site-packages), `pip install
# ./host-tools/python` with no index, then, from a directory outside the
# checkout, the installed package (not the source tree) with its own
# library, and the README's Python session run as written (doctest).
set -u
cd "$(dirname "$0")/../.."
ROOT=$PWD
PY=/usr/bin/python3
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
pass=0
fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }

if $PY -m venv --system-site-packages "$T/v" >"$T/log" 2>&1; then ok; else
    bad "python3 -m venv: $(tail -3 "$T/log")"
    echo "RESULT: $pass passed, $fail failed"
    exit 1
fi
# no index: the install must not need one
if env -u BRDFWAVE_LIB -u PYTHONPATH PIP_NO_INDEX=1 "$T/v/bin/pip" install \
    --disable-pip-version-check ./host-tools/python >"$T/log" 2>&1; then ok; else
    bad "pip install ./host-tools/python: $(tail -5 "$T/log")"
fi

mkdir -p "$T/elsewhere"
cd "$T/elsewhere"
run() { env -u BRDFWAVE_LIB -u PYTHONPATH "$T/v/bin/python" "$@"; }
if run - "$ROOT" >"$T/out" 2>&1 <<'EOF'; then ok; else bad "installed package: $(tail -5 "$T/out")"; fi
import os, sys
import numpy as np
import brdfwave
root = os.path.realpath(sys.argv[1])
here = os.path.realpath(brdfwave.__file__)
assert not here.startswith(root + os.sep), "imported from the checkout: " + here
from brdfwave import _lib
lib = os.path.realpath(_lib._find())
assert lib == os.path.join(os.path.dirname(here), "libbrdfwave.so"), lib
assert brdfwave.__version__
x = np.arange(12, dtype=np.uint16).reshape(2, 6)
m = brdfwave.decode(brdfwave.encode(x, wavelengths=[400, 410, 420, 430, 440, 450]),
                    integers=True)
assert np.array_equal(np.asarray(m), x) and list(m.wavelengths) == [400, 410, 420, 430, 440, 450]
EOF

# the README's session: the python block of its section "## Python"
$PY - "$ROOT/README.md" "$T/session.txt" <<'EOF'
import re, sys
text = open(sys.argv[1]).read()
sec = text.split("\n## Python\n", 1)[1].split("\n## ", 1)[0]
blocks = re.findall(r"```python\n(.*?)```", sec, re.S)
assert blocks and ">>>" in blocks[0], "no session in README's section Python"
open(sys.argv[2], "w").write(blocks[0])
EOF
if run - "$T/session.txt" >"$T/out" 2>&1 <<'EOF'; then ok; else bad "README session: $(head -30 "$T/out")"; fi
import doctest, sys
text = open(sys.argv[1]).read()
test = doctest.DocTestParser().get_doctest(text, {}, "README", "README.md", 0)
r = doctest.DocTestRunner(optionflags=doctest.NORMALIZE_WHITESPACE)
r.run(test)
print("%d examples, %d failed" % (r.tries, r.failures))
sys.exit(1 if r.failures or r.tries < 10 else 0)
EOF

echo "RESULT: $pass passed, $fail failed"
[ "$fail" = 0 ]
