#!/usr/bin/env bash
# Run one of the README's two commands on a fresh Debian of another release, in a throw-away root of this machine:
#   sudo bash scripts/debian_root.sh [forky] [test|demo]
# forky (Debian testing: Python 3.14, as Ubuntu 26.04) by default, or trixie, sid; `test` runs scripts/test.sh.
# It needs root (debootstrap, mount, chroot; debootstrap is installed from Debian when missing). The root gets only
# git, python3 and python3-venv; this repository's HEAD (committed work only) is cloned into it and the command runs
# there with an empty HOME, so setup.sh installs everything else itself, as on a new machine. The root stays in ROOT
# (default ${TMPDIR:-/tmp}/hexar-<release>-root) for another run; delete it when done.
set -euo pipefail
cd "$(dirname "$0")/.."
release="${1:-forky}"
what="${2:-test}"
case "$what" in test | demo) ;; *) echo "unknown command $what: use test or demo" >&2; exit 2 ;; esac
if [ "$(id -u)" != 0 ]; then
  echo "skipped: a Debian root needs root (debootstrap, mount, chroot)"
  exit 0
fi
if ! command -v debootstrap >/dev/null; then
  source scripts/apt_install.sh
  apt_install debootstrap || exit 1
fi
root="${ROOT:-${TMPDIR:-/tmp}/hexar-$release-root}"
mirror="${DEBIAN_MIRROR:-http://deb.debian.org/debian}"
if [ ! -x "$root/usr/bin/python3" ]; then
  # debootstrap knows every release after bookworm by sid's script
  script=/usr/share/debootstrap/scripts/sid
  [ -e "/usr/share/debootstrap/scripts/$release" ] && script="/usr/share/debootstrap/scripts/$release"
  debootstrap --variant=minbase --include=git,python3,python3-venv,ca-certificates "$release" "$root" "$mirror" \
    "$script" >"$root.debootstrap.log" 2>&1 || {
      # no root of that release can be made here (no network, an unknown release): nothing of HEXAR was tried
      echo "skipped: debootstrap $release failed (see $root.debootstrap.log)"; exit 0; }
fi
# what this machine trusts and resolves with (a proxy's CA, its DNS), as the machine's own installs do
cp /etc/resolv.conf "$root/etc/resolv.conf"
if compgen -G "/usr/local/share/ca-certificates/*.crt" >/dev/null; then
  cp /usr/local/share/ca-certificates/*.crt "$root/usr/local/share/ca-certificates/"
  chroot "$root" update-ca-certificates >/dev/null 2>&1
fi
# a mirror that serves a dated copy of testing has an expired Release file; the root is thrown away anyway
echo 'Acquire::Check-Valid-Until "false";' >"$root/etc/apt/apt.conf.d/99hexar-dated-mirror"
mounted=()
bind() { mount "$@" && mounted=("${@: -1}" "${mounted[@]}"); }
cleanup() { for m in "${mounted[@]}"; do umount -l "$m" || true; done; }
trap cleanup EXIT
# debootstrap made the root's own /dev nodes: /dev itself is never bound, so that a `rm -rf` of a root still
# mounted cannot reach this machine's devices
{ mountpoint -q "$root/proc" || bind -t proc proc "$root/proc"; } &&
  { mountpoint -q "$root/sys" || bind -t sysfs sys "$root/sys"; } &&
  { mountpoint -q "$root/dev/pts" || bind --bind /dev/pts "$root/dev/pts"; } &&
  { mountpoint -q "$root/dev/shm" || bind -t tmpfs tmpfs "$root/dev/shm"; } ||
  { echo "skipped: cannot mount /proc, /sys, /dev/pts and /dev/shm into $root here"; exit 0; }
rm -rf "$root/root/hexar"
git clone -q . "$root/root/hexar"
echo "running scripts/$what.sh on Debian $release ($(chroot "$root" python3 --version)) in $root"
start=$(date +%s)
rc=0
chroot "$root" /usr/bin/env -i PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin LANG=C.UTF-8 \
  TERM=dumb bash -c "cd /root/hexar && HOME=\$(mktemp -d) bash scripts/$what.sh" || rc=$?
echo "scripts/$what.sh on Debian $release: exit $rc in $(( $(date +%s) - start )) s"
exit "$rc"
