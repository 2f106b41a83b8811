#!/usr/bin/env bash
# The layers of src/ (issue 28, item 1): each folder includes only the folders it may depend on, and its CMake
# target links only the fluidbed targets it includes, so no include arrow runs back up a layer and the link
# lines say what the code uses. The allowed sets below are the picture of README.md (Layout) and docs/model.md
# section 0: change them together.
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/reliability.bash"
declare -A below=(
  [core]=""
  [parallel]="core"
  [io]="core"
  [numerics]="core parallel"
  [closures]="core"
  [dem]="core parallel numerics closures"
  [fluid]="core parallel numerics closures"
  [tfm]="core parallel numerics closures fluid"
  [coupling]="core parallel numerics closures dem fluid"
  [analysis]="core parallel numerics closures dem fluid tfm coupling"
  [config]="core parallel io numerics closures dem fluid tfm coupling analysis"
  [models]="core parallel io numerics closures dem fluid tfm coupling analysis config"
  [run]="core parallel io numerics closures dem fluid tfm coupling analysis config models"
)
check "every folder of src/ has its place in the layers" \
  bash -c "for d in $ROOT/src/*/; do d=\${d%/}; d=\${d##*/}; case ' ${!below[*]} ' in *\" \$d \"*) ;; *) echo \"  \$d\"; exit 1;; esac; done"
up="" wide=""
for layer in "${!below[@]}"; do
  used=$(grep -rhoE '^#include "[a-z_]+/' "$ROOT/src/$layer" | sed 's/#include "//; s#/$##' | sort -u | grep -vx "$layer")
  for u in $used; do
    [[ " ${below[$layer]} " == *" $u "* ]] || up+="$layer includes $u; "
  done
  # The fluidbed_* targets on the module's line in CMakeLists.txt, each one it must include.
  links=$(grep -E "^fluidbed_module\($layer( |\))" "$ROOT/CMakeLists.txt" | grep -oE 'fluidbed_[a-z_]+' | sed 's/fluidbed_//' | grep -v '^module$')
  for l in $links; do
    grep -qx "$l" <<<"$used" || wide+="$layer links $l without including it; "
  done
done
[[ -z $up ]] || echo "  against the layers: $up"
[[ -z $wide ]] || echo "  links wider than the includes: $wide"
check "no folder includes a folder above it" test -z "$up"
check "no CMake target links a fluidbed target it does not include" test -z "$wide"
finish
