#!/usr/bin/env bash
# The deployment tests (tests/server/deploy/) run the repository's nginx configuration in front of several
# server processes. Install Debian's nginx when it is missing (CI runs as root). The tests start their own
# nginx on free ports; the system service is not needed (stopped if the package started it).
set -u
if ! command -v nginx >/dev/null 2>&1 && [ ! -x /usr/sbin/nginx ]; then
  if [ "$(id -u)" = "0" ] && command -v apt-get >/dev/null 2>&1; then
    export DEBIAN_FRONTEND=noninteractive
    { apt-get install -y -q --no-install-recommends nginx >/dev/null 2>&1 \
      || { apt-get update -q >/dev/null 2>&1 && apt-get install -y -q --no-install-recommends nginx >/dev/null 2>&1; }; } \
      && { command -v service >/dev/null 2>&1 && service nginx stop >/dev/null 2>&1; true; } \
      || echo "ensure_nginx: could not install nginx; the deployment tests will be skipped (or fail with CI=true)" >&2
  fi
fi
exit 0
