# SPDX-License-Identifier: MIT
# shellcheck shell=bash
# apt.sh — sourced by the scripts that install packages. A Debian mirror
# caught mid-sync serves an index whose size or hash disagrees with its
# Release file ("File has unexpected size ... Mirror sync in progress?");
# apt-get update then exits non-zero although every other index arrived.
# These helpers retry, then go on with the lists that did arrive: a missing
# security or updates index only means older package versions, and a package
# that really cannot be found still fails at install or download.
#
# SNELL_APT_TRIES (default 3) and SNELL_APT_DELAY (seconds, default 15; the
# n-th retry waits n times that) tune the retries.

# snell_apt_retry WHAT COMMAND...: COMMAND up to SNELL_APT_TRIES times, the
# n-th retry after n times SNELL_APT_DELAY; 0 as soon as it succeeds.
snell_apt_retry() {
    local what=$1 tries=${SNELL_APT_TRIES:-3} delay=${SNELL_APT_DELAY:-15} i
    shift
    for ((i = 1; i <= tries; i++)); do
        "$@" && return 0
        if ((i < tries)); then
            echo "apt: $what failed (try $i of $tries); again in $((delay * i)) s" >&2
            sleep $((delay * i))
        fi
    done
    return 1
}

snell__apt_update_once() { DEBIAN_FRONTEND=noninteractive apt-get update -qq -o Acquire::Retries=3 "$@"; }

# snell_apt_update [apt-get options...]: 0 when an update succeeded, 1 when
# every try failed (the lists that did download are kept by apt).
snell_apt_update() {
    snell_apt_retry update snell__apt_update_once "$@" && return 0
    echo "apt: update failed ${SNELL_APT_TRIES:-3} times; going on with the package lists that arrived" >&2
    return 1
}

# One try of an install: update (tolerating a failed index), then install.
snell__apt_install_once() {
    snell_apt_update || true
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends -o Acquire::Retries=3 "$@"
}

# snell_apt_install PACKAGE...: an install that fails (a package list too
# old for the mirror's files) is retried after a fresh update.
snell_apt_install() {
    snell_apt_retry "install of $*" snell__apt_install_once "$@" && return 0
    echo "apt: could not install $*" >&2
    return 1
}
