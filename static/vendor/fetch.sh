#!/usr/bin/env bash
# Re-fetch the vendored JavaScript libraries from the npm registry, exactly at their pinned versions.
#
#   bash static/vendor/fetch.sh          # every package below
#   bash static/vendor/fetch.sh three    # one of them
#
# Each tarball comes through the npm client (`npm pack`), is checked against the registry's sha512 integrity
# pinned here, and only the listed files (plus the licence) are copied; SHA256SUMS in each folder lists what
# was copied, and tests/static/test_vendor.py checks the files against it. Nothing is fetched at run time.
set -euo pipefail
cd "$(dirname "$0")/../.."

# name  version  integrity (npm's dist.integrity)  destination  files inside the package
PACKAGES=(
  "three 0.187.0 sha512-Qiu7R+Cmh8CstZsY1uJOSWnVlfo7ZtNLV7mF8Jltk3LB3AtDu9cRZlcnRKkAk8Y4z6KKw35z7Y7Urd7jWY8etA== static/vendor/three build/three.module.js build/three.core.js LICENSE"
  "iwer 2.5.0 sha512-grq7iMyWo4s2DYnATKLPPoAByhcNuwLjMHHOILrFU9q8EGHIEzHyUuq1mz+9Xqy6+xrYPn3Ho8Z9eymZCE+D6w== tests/static/vendor/iwer build/iwer.min.js LICENSE"
)

fetch() {
  local name=$1 version=$2 integrity=$3 dest=$4
  shift 4
  local tmp
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' RETURN
  npm pack --silent --pack-destination "$tmp" "$name@$version" >/dev/null
  local tarball="$tmp/$name-$version.tgz"
  local actual="sha512-$(openssl dgst -sha512 -binary "$tarball" | base64 -w0)"
  if [[ "$actual" != "$integrity" ]]; then
    echo "$name@$version: integrity mismatch: got $actual, pinned $integrity" >&2
    return 1
  fi
  tar -xzf "$tarball" -C "$tmp"
  rm -rf "$dest"
  mkdir -p "$dest"
  local file
  for file in "$@"; do
    cp "$tmp/package/$file" "$dest/$(basename "$file")"
  done
  echo "$name@$version" >"$dest/VERSION"
  (cd "$dest" && sha256sum -- $(for f in "$@"; do basename "$f"; done) VERSION >SHA256SUMS)
  echo "$name@$version -> $dest ($# files, integrity ok)"
}

for entry in "${PACKAGES[@]}"; do
  read -r -a fields <<<"$entry"
  if [[ $# -eq 0 || " $* " == *" ${fields[0]} "* ]]; then
    fetch "${fields[@]}"
  fi
done
