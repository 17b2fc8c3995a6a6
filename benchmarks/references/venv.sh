#!/usr/bin/env bash
# Creates (once) the Python environment that renders the Mitsuba 3 references
# and prints its python. Mitsuba 3 and Dr.Jit are not Debian packages, so they
# come from PyPI, pinned. The LLVM variants (llvm_ad_rgb, vectorised on every
# core) need Debian's libllvm19 (Dr.Jit 1.5's kernels do not compile with
# Debian's LLVM 15: "Cannot select fminimum"); scalar_rgb needs nothing more.
# Never run at build or test time: the tests compare with committed EXRs.
#
# Usage: benchmarks/references/venv.sh [VENV_DIR]   (default: build/.venv-mitsuba)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
venv=${1:-$root/build/.venv-mitsuba}
if [ ! -x "$venv/bin/python" ] || ! "$venv/bin/python" -c 'import mitsuba' 2>/dev/null; then
  sudo=(); [ "$(id -u)" = 0 ] || sudo=(sudo)
  if ! python3 -c 'import venv, ensurepip' 2>/dev/null; then "${sudo[@]}" apt-get install -y python3-venv >&2; fi
  if ! ls /usr/lib/*/libLLVM-19.so >/dev/null 2>&1; then "${sudo[@]}" apt-get install -y libllvm19 >&2; fi
  python3 -m venv "$venv" >&2
  "$venv/bin/pip" install --quiet 'mitsuba==3.9.1' 'drjit==1.5.0' numpy >&2
fi
echo "$venv/bin/python"
