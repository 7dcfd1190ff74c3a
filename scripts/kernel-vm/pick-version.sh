# Sourced by fetch-kernel.sh (and its test, tests/scripts/check_kernel_versions.sh);
# needs log() and die() from the caller.
# The packages of one kernel are not always published at one version (the
# image at 6.1.192-2 while kbuild is only at 6.1.192-3, say): each is taken
# at the image's exact version where the archive has it, else at the newest
# version of the same upstream release (headers, kbuild and source of one
# upstream release build modules for its image).
versions_of() {  # every version apt offers for $1, one a line
  apt-cache madison "$1" 2>/dev/null | awk -F'|' '{gsub(/ /, "", $2); print $2}'
}
pick_version() {  # $1 package, $2 the image's version -> the version to fetch
  local pkg=$1 want=$2 upstream=${2%-*} v best=""
  local offered
  offered=$(versions_of "$pkg")
  if grep -qxF -- "$want" <<<"$offered"; then
    echo "$want"
    return 0
  fi
  while read -r v; do
    [[ -n "$v" && "${v%-*}" == "$upstream" ]] || continue
    if [[ -z "$best" ]] || dpkg --compare-versions "$v" gt "$best"; then best=$v; fi
  done <<<"$offered"
  if [[ -z "$best" ]]; then
    die "the archive has no ${pkg} at ${want} nor at any ${upstream}-* (it offers: $(tr '\n' ' ' <<<"${offered:-nothing}"))"
  fi
  log "${pkg}: no ${want} in the archive, taking ${best} (same upstream release ${upstream})"
  echo "$best"
}
