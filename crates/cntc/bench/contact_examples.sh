#!/usr/bin/env bash
# contact_examples.sh CONTACT_DIR CONTACT_LIB [RUNS]
#
# Times CONTACT's two Python examples of its library, python_mbench.py and
# python_tractcurv.py, end to end (whole processes), on CONTACT's own
# library and on railcontact's (crates/cntc, built here with build-lib.sh)
# in process and forwarded to a railcontact server (a release build
# started here on a free loopback port, memory-only), the three
# alternated RUNS times (default 5); prints each run, the medians and
# CONTACT's over each of ours.
#
#   CONTACT_DIR  a checkout of CONTACT (eve70a/CONTACT): its python_intfc/
#                and examples/ are used, unchanged but for the three mends
#                the examples need to run at all (below)
#   CONTACT_LIB  CONTACT's contact_addon_linux64.so, built from that
#                checkout (e.g. with a gfortran + FFTW build of its
#                `make PROD=clib_l64`)
#
# Mends, applied to copies: `import importlib.util` (the examples use it
# without importing it), and `setmaterialparameters` in place of
# `setmaterialproperties` and `setinterfaciallayer`, which CONTACT's
# python_intfc no longer has (as CONTACT's Matlab examples now call it).
# python_tractcurv.py runs its four curves (curve 2: an interfacial layer
# with falling friction). Needs python3 with numpy.
set -euo pipefail
[ $# -ge 2 ] || { sed -n '2,24p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
SRC=$(cd "$1" && pwd); THEIRS=$(cd "$(dirname "$2")" && pwd)/$(basename "$2"); RUNS=${3:-5}
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd)
[ -d "$SRC/python_intfc" ] && [ -f "$SRC/examples/python_mbench.py" ] \
   || { echo "contact_examples.sh: $SRC has no python_intfc/ or examples/python_mbench.py" >&2; exit 2; }
[ -f "$THEIRS" ] || { echo "contact_examples.sh: no library $THEIRS" >&2; exit 2; }
python3 -c 'import numpy' 2>/dev/null \
   || { echo "contact_examples.sh: python3 needs numpy (python3 -m venv v && v/bin/pip install numpy)" >&2; exit 2; }

WORK=$(mktemp -d); SERVER_PID=
trap '[ -n "$SERVER_PID" ] && kill "$SERVER_PID" 2>/dev/null; rm -rf "$WORK"' EXIT
"$ROOT/crates/cntc/build-lib.sh" "$WORK/ours-lib" >/dev/null
(cd "$ROOT" && cargo build --release --quiet --bin railcontact)
RAILCONTACT_DATA_DIR= "$ROOT/target/release/railcontact" serve --listen 127.0.0.1:0 \
   >"$WORK/server.out" 2>"$WORK/server.err" &
SERVER_PID=$!
for _ in $(seq 100); do grep -q "listening on" "$WORK/server.out" 2>/dev/null && break; sleep 0.1; done
SERVER=$(sed -n 's/^railcontact listening on //p' "$WORK/server.out")
[ -n "$SERVER" ] || { echo "contact_examples.sh: the server did not start:"; cat "$WORK/server.err"; exit 1; }
for who in theirs ours; do
   d=$WORK/$who; mkdir -p "$d/bin"
   cp -r "$SRC/python_intfc" "$d/"
   cp "$SRC"/examples/MBench_* "$d/"
   if [ $who = theirs ]; then cp "$THEIRS" "$d/bin/contact_addon_linux64.so"
   else cp "$WORK/ours-lib/contact_addon_linux64.so" "$d/bin/"; fi
   for ex in python_mbench.py python_tractcurv.py; do
      python3 - "$SRC/examples/$ex" "$d/$ex" <<'PY'
import re, sys
s = open(sys.argv[1]).read()
s = s.replace("import importlib\n", "import importlib\nimport importlib.util\n", 1)
s = re.sub(r"cntc\.setmaterialproperties\((\w+), *([^,]+), *gg, *poiss, *gg, *poiss\)",
           r"cntc.setmaterialparameters(\1, \2, 0, [poiss, poiss, gg, gg])", s)
s = re.sub(r"cntc\.setinterfaciallayer\((\w+), *(\w+), *imeth, *params\)",
           r"cntc.setmaterialparameters(\1, \2, imeth, [poiss, poiss, gg, gg] + params)", s)
open(sys.argv[2], "w").write(s)
PY
   done
done

now() { date +%s.%N; }
declare -A times
WHO="theirs ours forwarded"
for ((k = 1; k <= RUNS; k++)); do
   for ex in python_mbench.py python_tractcurv.py; do
      for who in $WHO; do
         dir=$who; env=()
         if [ $who = forwarded ]; then dir=ours; env=(RAILCONTACT_CNTC_SERVER="$SERVER"); fi
         t0=$(now)
         (cd "$WORK/$dir" && env "${env[@]}" LD_LIBRARY_PATH=${LD_LIBRARY_PATH:-/nonexistent} \
             python3 "$ex" >"$WORK/$who-$ex.log" 2>&1) \
            || { echo "$who $ex failed:"; tail -5 "$WORK/$who-$ex.log"; exit 1; }
         t=$(python3 -c "print($(now) - $t0)")
         times[$who-$ex]+="$t "
         printf 'run %d %-20s %-9s %7.3f s\n' "$k" "$ex" "$who" "$t"
      done
   done
done
# The examples print the same numbers in process and forwarded (the
# calculation times aside).
for ex in python_mbench.py python_tractcurv.py; do
   diff <(grep -viE "time|tcpu|twall" "$WORK/ours-$ex.log") <(grep -viE "time|tcpu|twall" "$WORK/forwarded-$ex.log") >/dev/null \
      || echo "warning: $ex printed other numbers forwarded than in process"
done
median() { tr ' ' '\n' | grep . | sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }
for ex in python_mbench.py python_tractcurv.py; do
   mt=$(echo "${times[theirs-$ex]}" | median); mo=$(echo "${times[ours-$ex]}" | median)
   mf=$(echo "${times[forwarded-$ex]}" | median)
   printf '%-20s median CONTACT %7.3f s, railcontact in process %7.3f s (ratio %.1f), forwarded %7.3f s (ratio %.1f)\n' \
      "$ex" "$mt" "$mo" "$(python3 -c "print($mt / $mo)")" "$mf" "$(python3 -c "print($mt / $mf)")"
done
