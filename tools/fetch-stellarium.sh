#!/bin/sh
# Downloads Debian's stellarium-data (about 250 MB) and unpacks only the
# files libsky's texture and catalogue tools read, into $1.
set -e
dest=${1:?usage: fetch-stellarium.sh DIR}
want="./usr/share/stellarium/textures/earth-clouds.png ./usr/share/stellarium/textures/moon.png ./usr/share/stellarium/stars/default/hip_pm.dat ./usr/share/doc/stellarium-data/copyright"
if [ -f "$dest/usr/share/stellarium/textures/earth-clouds.png" ]; then exit 0; fi
mkdir -p "$dest"
cd "$dest"
apt-get download stellarium-data
dpkg-deb --fsys-tarfile stellarium-data_*.deb | tar -x $want
rm -f stellarium-data_*.deb
