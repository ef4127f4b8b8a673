#!/usr/bin/env bash
# apt_install PKG...: install Debian packages, waiting for a package manager another process holds.
# Sourced by setup.sh. apt waits up to HEXAR_APT_LOCK_WAIT s for the dpkg lock itself; a run that still fails
# (lock held longer, "cannot access archive", a mirror hiccup) is retried HEXAR_APT_TRIES times, and then one line
# says what to do instead of apt's own pages of errors, which are kept in a log file.
apt_install() {
  local sudo="" tries="${HEXAR_APT_TRIES:-3}" delay="${HEXAR_APT_RETRY_DELAY:-20}" wait="${HEXAR_APT_LOCK_WAIT:-120}"
  [ "$(id -u)" = 0 ] || sudo=sudo
  local log
  log="$(mktemp -t hexar-apt.XXXXXX)"
  local i
  for ((i = 1; i <= tries; i++)); do
    if $sudo apt-get -o DPkg::Lock::Timeout="$wait" update -qq >>"$log" 2>&1 \
      && $sudo env DEBIAN_FRONTEND=noninteractive apt-get -o DPkg::Lock::Timeout="$wait" install -y -qq "$@" >>"$log" 2>&1; then
      rm -f "$log"
      return 0
    fi
    [ "$i" -lt "$tries" ] && sleep "$delay"
  done
  local why="it failed"
  grep -qiE 'could not get lock|unable to acquire the dpkg|is another process using it|cannot access archive' "$log" \
    && why="another process holds the package manager"
  echo "ERROR: could not install the Debian packages $* ($why, $tries tries); let the other apt/dpkg finish (or run 'sudo dpkg --configure -a'), then run this again; apt's output is in $log" >&2
  return 1
}
