#!/usr/bin/env bash
# The dependency rule of docs/design.md: the engine includes no pass and no contract, a contract
# includes only the engine and contracts, and a family includes only the engine, the contracts
# and itself. Prints every include that breaks it and fails if there is one.
set -euo pipefail
root="$1"
cd "$root"
status=0
families=$(find passes -mindepth 1 -maxdepth 1 -type d ! -name contracts -printf '%f\n' | sort)

# Prints the includes of the files under $1 (C++ and GLSL) as "file:line: path".
includes() {
  grep -rnE --include='*.cpp' --include='*.hpp' --include='*.glsl' --include='*.comp' \
    --include='*.vert' --include='*.geom' --include='*.frag' '^[[:space:]]*#include "' "$@" |
    sed -E 's/^([^:]+:[0-9]+):[[:space:]]*#include "([^"]+)".*/\1: \2/' || true
}

report() {
  while IFS= read -r line; do
    [ -z "$line" ] && continue
    echo "$1: $line"
    status=1
  done
}

report "engine includes a pass or contract" < <(includes engine shaders/lib | grep -E ': passes/|: contracts/' || true)
report "contract includes a family" < <(
  includes passes/contracts shaders/contracts | grep -vE ': (engine|passes/contracts|lib|contracts)/' || true)
for family in $families; do
  dirs=(passes/"$family")
  [ -d shaders/"$family" ] && dirs+=(shaders/"$family")
  report "$family includes another family" < <(
    includes "${dirs[@]}" |
      grep -vE ": (engine|passes/contracts|passes/$family|lib|contracts|$family)/" || true)
done
exit $status
