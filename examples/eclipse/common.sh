# Shared by the eclipse examples: the umbra program and the output folder.
# UMBRA: the program (default: umbra on the PATH, else the build tree's).
# UMBRA_EXAMPLE_FLAGS: extra flags for every run, e.g. "--draft-tables --size 64" for a quick look.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
if [ -z "${UMBRA:-}" ]; then
  if command -v umbra >/dev/null; then UMBRA=umbra; else UMBRA="$here/../../build/app/cli/umbra"; fi
fi
out="${1:-eclipse-out}"
mkdir -p "$out"
read -r -a extra <<< "${UMBRA_EXAMPLE_FLAGS:-}"
