#!/bin/sh
# Installs the Debian packages libsky's build, demo and tests need, when
# they are missing: apt-get as root, sudo otherwise, a clear message if
# neither is possible. Packages given as arguments are wanted too (make
# examples passes the engines').
set -e
PACKAGES="gcc make libc6-dev libgl-dev libosmesa6-dev libegl-dev libegl-mesa0 libglfw3-dev libstb-dev liberfa-dev xvfb xauth pkgconf cmake $*"
missing=""
for p in $PACKAGES; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
[ -z "$missing" ] && exit 0
echo "deps: installing$missing"
if [ "$(id -u)" = 0 ]; then
    SUDO=""
elif command -v sudo >/dev/null 2>&1; then
    SUDO="sudo"
else
    echo "deps: missing packages:$missing" >&2
    echo "deps: run as root (or install sudo) so they can be installed with apt-get" >&2
    exit 1
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends $missing
