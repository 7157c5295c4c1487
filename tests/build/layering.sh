#!/usr/bin/env bash
# The modules' layering: a module includes headers of the modules below it only. Each line of
# the table names a folder and what its sources may include (besides itself); a folder not in
# the table, or an include outside its line, fails the test with the file and the include.
# cli/, bench/ and tests/ sit on top and may include anything, but for cli/workers/ (below).
set -euo pipefail
root="${1:?usage: layering.sh SOURCE_DIR}"
cd "$root"

declare -A allowed=(
  [core]=""
  [typed_json]="core"
  [casefile]="core typed_json"
  [ref]="core"
  [driver_models]="core"
  [gl_harness]="core"
  [image_io]=""
  [compare]="core"
  [report]="core compare image_io typed_json"
  [check]="core ref compare driver_models gl_harness"
  [identify]="core ref compare gl_harness"
  [selftest]="core check compare driver_models gl_harness report"
  [campaign]="core casefile selftest compare"
  [export]="core compare"
)

status=0
for dir in */; do
  dir="${dir%/}"
  case "$dir" in cli | bench | tests | scripts | cases | build* | bundle | out | .*) continue ;; esac
  compgen -G "$dir/*.[ch]pp" >/dev/null || compgen -G "$dir/*.h" >/dev/null || continue
  if [[ ! -v "allowed[$dir]" ]]; then
    echo "$dir/: a module not in tests/build/layering.sh's table: add it with what it may include"
    status=1
    continue
  fi
  while IFS=: read -r file include; do
    module="${include%%/*}"
    [ "$module" = "$dir" ] && continue
    if [[ ! -v "allowed[$module]" ]] && [ "$module" != cli ]; then continue; fi  # a library's own
    if [[ " ${allowed[$dir]} " != *" $module "* ]]; then
      echo "$file includes \"$include\": $dir/ may include only ${allowed[$dir]:-nothing of ours}"
      status=1
    fi
  done < <(grep -oE '^#include "[a-z_]+/[^"]+"' "$dir"/*.[ch]pp "$dir"/*.h 2>/dev/null |
    sed -E 's/:#include "/:/; s/"$//')
done

# cli/workers/, the process engine: it may include of the rest of cli/ only the run's options
# (session.hpp) and the identify command a worker runs (identify.hpp); the rest of cli/ may
# include of it only its interface (workers.hpp) and the child process's environment and log
# header (process.hpp), never the pool or the protocol.
while IFS=: read -r file include; do
  case "$include" in cli/workers/* | cli/session.hpp | cli/identify.hpp) ;;
  *) echo "$file includes \"$include\": cli/workers/ may include of cli/ only session.hpp and identify.hpp"; status=1 ;;
  esac
done < <(grep -oE '^#include "cli/[^"]+"' cli/workers/*.[ch]pp 2>/dev/null | sed -E 's/:#include "/:/; s/"$//')
while IFS=: read -r file include; do
  case "$include" in cli/workers/workers.hpp | cli/workers/process.hpp) ;;
  *) echo "$file includes \"$include\": cli/ may include of cli/workers/ only workers.hpp and process.hpp"; status=1 ;;
  esac
done < <(grep -oE '^#include "cli/workers/[^"]+"' cli/*.[ch]pp 2>/dev/null | sed -E 's/:#include "/:/; s/"$//')
exit $status
